// CONTROL: breaks no rule. Every harness check must pass (descriptor, premultiplied, coverage,
// finite, determinism, state isolation, disconnected parameters, no crash, no timeout).
// Coverage-preserving: alpha is texelFetch'ed from "previous" and written back unchanged;
// colour is only scaled by non-negative factors, so rgb stays 0 wherever a is 0. Both
// parameters visibly change the output on any non-empty input.
#include <acetate/effect.hpp>

class WellBehaved final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.well_behaved";
        e.display_name = "Harness control: well behaved";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {
            {"gain", "multiplies the colour", 1.0f, 0.0f, 2.0f},
            {"warmth", "shifts the colour towards red and away from blue", 0.2f, 0.0f, 1.0f},
        };
        // The host accepts only the preset names low, medium, high and ultra.
        e.presets = {{"low", {{"gain", 0.8f}}}, {"high", {{"gain", 1.5f}}}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "tint",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec3 warm = mix(vec3(1.0), vec3(1.1, 1.0, 0.9), param_warmth);
    out_color = vec4(prev.rgb * param_gain * warm, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(WellBehaved)
