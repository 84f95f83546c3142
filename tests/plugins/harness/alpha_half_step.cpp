// BROKEN on purpose: rule 2a, "coverage-preserving: out.a == in.a, bit-exact". For
// 0 < a < 1 it writes the next half-float above a (exactly one RGBA16F step); opaque and
// transparent pixels are untouched and colour is only scaled by `gain`. Caught by: the
// COVERAGE check only (the smallest possible alpha change: a check with any tolerance misses it).
#include <acetate/effect.hpp>

class AlphaHalfStep final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.alpha_half_step";
        e.display_name = "Harness: alpha one half-float step up";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"gain", "multiplies the colour", 1.0f, 0.0f, 2.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "nudge",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float a = prev.a;
    if (a > 0.0 && a < 1.0)
        a = unpackHalf2x16(packHalf2x16(vec2(a, 0.0)) + 1u).x;  // the next half-float up
    out_color = vec4(prev.rgb * param_gain, a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(AlphaHalfStep)
