// Two presets of its own naming, "draft" and "final" (named_presets in the SDK), neither of the
// four quality names: the host accepts them, and acetate-bench, given no --presets, runs both
// and measures error against the last, "final" (tests/e2e/bench_cli_test.cpp).
#include <acetate/effect.hpp>

namespace {

inline constexpr acetate::sdk::FloatParam kStrength{"strength", "how much of the colour is kept",
                                                    1.0f, 0.0f, 1.0f};

}  // namespace

class NamedPresets final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.named_presets";
        e.display_name = "Test: presets named draft and final";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {kStrength};
        e.presets = acetate::sdk::named_presets({"draft", "final"}, {{kStrength, {0.5f, 0.9f}}});
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "keep",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * param_strength, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(NamedPresets)
