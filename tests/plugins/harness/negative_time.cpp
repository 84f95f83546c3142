// BROKEN on purpose: a negative time. A glow builds up with the square root of time,
// s = sqrt(t) / (1 + sqrt(t)), assuming time starts at 0; at t < 0 the root is NaN over the
// whole floor. Otherwise colour is scaled by 0.85 to 1 and alpha is kept. Caught by: FINITE in
// time/negative (-2.5 s) only, and in a combined/* point drawn with a negative time.
#include <acetate/effect.hpp>

class NegativeTime final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.negative_time";
        e.display_name = "Harness: square root of time";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "build_up",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float root = sqrt(acetate_time);  // NaN before time 0
    out_color = vec4(prev.rgb * (0.85 + 0.15 * root / (1.0 + root)), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(NegativeTime)
