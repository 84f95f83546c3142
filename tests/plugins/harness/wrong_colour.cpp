// BREAKS: colour, and nothing else. The well_behaved control with its warmth turned the wrong
// way (towards blue, away from red): alpha is kept, rgb is a non-negative scale of the input
// (0 wherever a is 0), deterministic, both parameters connected. Every contract check passes;
// only the comparison with references blessed from the correct tint (`golden`) can catch it
// (tests/harness/harness_golden_test.cpp).
#include <acetate/effect.hpp>

class WrongColour final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.wrong_colour";
        e.display_name = "Harness battery: wrong colour, right alpha";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {
            {"gain", "multiplies the colour", 1.0f, 0.0f, 2.0f},
            {"warmth", "meant to shift the colour towards red; shifts it towards blue", 0.2f, 0.0f,
             1.0f},
        };
        e.presets = {{"low", {{"gain", 0.8f}}}, {"high", {{"gain", 1.5f}}}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "tint",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec3 warm = mix(vec3(1.0), vec3(0.9, 1.0, 1.1), param_warmth);
    out_color = vec4(prev.rgb * param_gain * warm, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(WrongColour)
