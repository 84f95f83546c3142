// BROKEN on purpose: a result GLSL leaves undefined. A sheen is clamp(log(-1 - a), 0, 1), a sign
// slip for log(1 + a): the logarithm of a negative number is NaN, and clamp() of a NaN is
// undefined. llvmpipe's clamp returns a finite value, so every image looks right here; another
// driver may give NaN. Colour is scaled by 0.9 to 1 and alpha is kept. Caught by: the
// UNDEFINED-RESULTS check only (in every contract case,
// rendered once more with a checked clamp that returns NaN for a NaN operand).
#include <acetate/effect.hpp>

class HiddenNan final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.hidden_nan";
        e.display_name = "Harness: a NaN hidden by clamp";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "sheen",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float sheen = clamp(log(-1.0 - prev.a), 0.0, 1.0);  // meant log(1.0 + prev.a)
    out_color = vec4(prev.rgb * (0.9 + 0.1 * sheen), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(HiddenNan)
