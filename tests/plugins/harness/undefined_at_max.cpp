// BROKEN on purpose: a result GLSL leaves undefined, but only away from the defaults. A sheen
// is clamp(log(0.5 - amount) + 2, 0, 1): finite for `amount` below 0.5 (the default is 0.2), the
// logarithm of a negative number (NaN) above it, and clamp() of a NaN is undefined. llvmpipe's
// clamp returns a finite value, so every image looks right here. Colour is scaled by 0.85 to 1
// and alpha is kept.
// Caught by: the UNDEFINED-RESULTS check only, and only in cases that set amount above 0.5
// (params/max, the sweep of amount, combined points): the checked built-ins run in every
// contract case, not only at the defaults.
#include <acetate/effect.hpp>

class UndefinedAtMax final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.undefined_at_max";
        e.display_name = "Harness: a NaN hidden by clamp at high amounts";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"amount", "how much sheen", 0.2f, 0.0f, 1.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "sheen",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float sheen = clamp(log(0.5 - param_amount) + 2.0, 0.0, 1.0);
    out_color = vec4(prev.rgb * (0.85 + 0.1 * sheen + 0.05 * param_amount), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(UndefinedAtMax)
