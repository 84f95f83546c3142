#version 450
// Floor target -> accumulation. A pure pass-through (docs/design.md, L-pass-through): the
// Composite pipeline's stencil test (EQUAL 1) gates it to the floor's coverage (CompositeByAlpha
// has no gate; see below) and the blend (One, OneMinusSrcAlpha) does "over". CompositeByAlpha
// is the variant with GATE_BY_ALPHA defined (host_pipelines.cpp inserts it after #version), not
// a branch on a push constant, which lavapipe would evaluate for every pixel.
layout(push_constant) uniform Push {  // CompositePushConstants (render/host_pipelines.hpp)
    uint violation_slot;  // the floor's counter
} pc;
layout(set = 0, binding = 0) uniform sampler2D floor_color;
layout(set = 0, binding = 2) buffer Violations { uint count[]; } violations;
layout(location = 0) out vec4 color;
// The stencil test must run before this shader, or fragments the gate rejects would still be
// counted as violations by the atomic below.
layout(early_fragment_tests) in;

void main() {
    vec4 c = texelFetch(floor_color, ivec2(gl_FragCoord.xy), 0);
    bool bad = (c.a <= 0.0 && any(notEqual(c.rgb, vec3(0.0)))) || any(isnan(c)) || any(isinf(c));
    if (bad) atomicAdd(violations.count[pc.violation_slot], 1u);
#ifdef GATE_BY_ALPHA
    // A coverage-expanding effect may have drawn past the tiles' stencil, so pixels it left
    // fully transparent are dropped instead (over with (0,0,0,0) is a no-op anyway; colour at
    // alpha 0 is still composited, and counted above).
    if (c == vec4(0.0)) discard;
#endif
    color = c;
}
