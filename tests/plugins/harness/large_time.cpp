// BROKEN on purpose: a large time. A fade-in completing over about 1000 s, 1 - exp(-t / 1000),
// is rearranged to (e - 1) / e with e = exp(t / 1000); past t = 88.7e3 s e overflows single
// precision and the fade is Inf / Inf = NaN over the whole floor. Otherwise colour is scaled by
// 0.9 + 0.1 * fade, at most 1 (0.89 at -100 s, the earliest time drawn) and alpha is kept.
// Caught by: FINITE in time/large (10^5 s) only, and in a combined/* point drawn near 10^5 s.
#include <acetate/effect.hpp>

class LargeTime final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.large_time";
        e.display_name = "Harness: exp of time";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "fade_in",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float e = exp(acetate_time * 0.001);  // infinite past 88.7e3 s
    float fade = (e - 1.0) / e;
    out_color = vec4(prev.rgb * (0.9 + 0.1 * fade), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(LargeTime)
