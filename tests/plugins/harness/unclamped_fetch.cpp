// BREAKS rule 4 (no undefined results): it reads the pixel to its right with texelFetch without
// clamping, so at the canvas's right edge it reads outside `previous`. lavapipe reads zeros
// there, which looks like a transparent border; Vulkan leaves the value undefined. Every output
// here is valid: the colour is scaled by a factor in [1, 1.5] that grows with the step in alpha
// to the right, and alpha is kept. Caught by `undefined-results` (the checked texelFetch
// reads NaN outside the texture) in every contract case: every canvas has a right edge.
#include <acetate/effect.hpp>

class UnclampedFetch final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.unclamped_fetch";
        e.display_name = "Harness battery: a texelFetch past the canvas's edge";
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"edge", "how much an alpha step brightens", 0.5f, 0.1f, 0.5f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "edges",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 prev = texelFetch(previous, p, 0);
    vec4 right = texelFetch(previous, p + ivec2(1, 0), 0);
    float step_up = abs(right.a - prev.a);
    out_color = vec4(prev.rgb * (1.0 + param_edge * step_up), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(UnclampedFetch)
