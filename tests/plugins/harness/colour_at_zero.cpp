// BROKEN on purpose: rule 3, "rgb == 0 wherever a == 0". Where previous is transparent
// (a == 0) it writes colour (0.25, 0, 0) with alpha 0; alpha itself is passed through, so the
// effect stays coverage-preserving. Caught by: the PREMULTIPLIED check only.
#include <acetate/effect.hpp>

class ColourAtZero final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.colour_at_zero";
        e.display_name = "Harness: colour at zero alpha";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"gain", "multiplies the colour of covered pixels", 1.0f, 0.0f, 2.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "stain",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    if (prev.a == 0.0)
        out_color = vec4(0.25, 0.0, 0.0, prev.a);  // colour without coverage
    else
        out_color = vec4(prev.rgb * param_gain, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(ColourAtZero)
