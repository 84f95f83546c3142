// CORRECT (a control): a coverage-preserving global effect, a colour grade on the composite
// (out.rgb = prev.rgb * 0.8, alpha kept bit for bit).
// Must reach VALIDATED with bloom (a coverage-expanding global effect) INTEGRATED beside it:
// the integration stack runs bloom first, and this effect is judged on its own input (the
// composite bloom left, with grown alpha) and output, not on the composite before every
// global effect (tests/harness/harness_stages_test.cpp).
#include <acetate/effect.hpp>

class GlobalGrade final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.global_grade";
        e.display_name = "Harness: global colour grade";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.scope = ACETATE_SCOPE_GLOBAL;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "grade",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * 0.8, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(GlobalGrade)
