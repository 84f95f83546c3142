#version 450
// Test hook: paints a colour inside or outside the floor's coverage (the pipeline's stencil test
// picks which). Stands in for an effect that breaks the contract, so tests can show what the
// stencil gate and the violation counters do with it.
layout(push_constant) uniform Push {
    vec4 rect;
    vec4 tint;
    vec2 canvas;
    uint floor_index;
    uint tint_mode;
} pc;
layout(location = 0) out vec4 color;
void main() { color = pc.tint; }
