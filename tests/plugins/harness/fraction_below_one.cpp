// CORRECT (a control): relies on acetate_time_fraction being below 1, as the plugin guide
// promises. A flicker fades as -log(1 - f) over the second; at 2.99999999 s the fraction
// 0.99999999 would round to 1.0 as a float, and the logarithm of 0 would make the flicker
// NaN, but the host keeps the fraction below 1 (the largest float under 1). Colour is scaled by
// 0.9 to 1 and alpha is kept.
// Must pass every check, time/fraction-rounds-up included: it holds the host to its promise.
#include <acetate/effect.hpp>

class FractionBelowOne final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.fraction_below_one";
        e.display_name = "Harness: assumes a time fraction below 1";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "flicker",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float f = -log(1.0 - acetate_time_fraction);
    out_color = vec4(prev.rgb * (0.9 + 0.1 * f / (1.0 + f)), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(FractionBelowOne)
