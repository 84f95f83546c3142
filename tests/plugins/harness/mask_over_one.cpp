// BROKEN on purpose: a mask above 1. A shoreline fades as sqrt(1 - m), assuming a mask never
// exceeds 1; masks are data and the format does not bound them, and above 1 the root of a
// negative number is NaN. Otherwise colour is scaled by 0.8 to 1 and alpha is kept.
// Caught by: FINITE in masks/above-one only, and in a combined/* point drawn with it.
#include <acetate/effect.hpp>

class MaskOverOne final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.mask_over_one";
        e.display_name = "Harness: assumes a mask within [0, 1]";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.masks = {"water"};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "shore",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float m = texelFetch(mask_water, ivec2(gl_FragCoord.xy), 0).r;
    out_color = vec4(prev.rgb * (0.8 + 0.2 * sqrt(1.0 - m)), prev.a);
}
)",
                    .inputs = {"previous", "mask.water"}});
    }
};
ACETATE_REGISTER_EFFECT(MaskOverOne)
