#version 450
// Test hook: paints a colour wherever the floor has NO coverage (stencil != 1 in the pipeline).
// Stands in for an effect that breaks the contract, to prove the composite's stencil gate.
layout(push_constant) uniform Push {
    vec4 rect;
    vec4 tint;
    vec2 canvas;
    uint floor_index;
    uint tint_mode;
} pc;
layout(location = 0) out vec4 color;
void main() { color = pc.tint; }
