#version 450
// Test hook: paints a colour inside or outside the floor's coverage (the pipeline's stencil test
// picks which). Stands in for an effect that breaks the contract, so tests can show what the
// stencil gate and the violation counters do with it.
layout(push_constant) uniform Push {  // InjectPushConstants (render/host_pipelines.hpp)
    vec4 colour;  // premultiplied
} pc;
layout(location = 0) out vec4 color;
void main() { color = pc.colour; }
