// BROKEN on purpose: a parameter strictly inside its range. `blend` (0..1, default 0) picks
// the dark look at or below 0.25 and the plain look at or above 0.75; the crossfade between
// them was pasted from the upper band and takes log(blend - 0.75), the logarithm of a negative
// number, NaN for every value in (0.25, 0.75). The ends, the default and the disconnected-
// parameter case (minimum and maximum) never reach it. Caught by: FINITE in
// params/sweep-blend (at 1/3) only, and in a combined/* point that draws blend inside the band.
#include <acetate/effect.hpp>

class ParamInterior final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.param_interior";
        e.display_name = "Harness: NaN inside the parameter's range";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"blend", "from the dark look (0) to the plain look (1)", 0.0f, 0.0f, 1.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "looks",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float w;
    if (param_blend <= 0.25)
        w = 0.0;  // the dark look
    else if (param_blend >= 0.75)
        w = 1.0;  // the plain look
    else
        w = 0.5 + 0.25 * log(param_blend - 0.75);  // meant log(param_blend - 0.25) ...
    out_color = vec4(prev.rgb * mix(0.8, 1.0, w), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(ParamInterior)
