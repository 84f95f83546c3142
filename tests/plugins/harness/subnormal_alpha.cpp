// BROKEN on purpose: subnormal alpha. A glow keeps its source, the floor at half strength
// (0.5 * prev, premultiplied), in an intermediate target, RGBA16F like every target by
// default, and tints the floor by the source's straight colour, rgb / a. It skips empty
// pixels by their colour (rgb == 0) rather than their alpha, trusting that premultiplied
// colour is 0 wherever alpha is. Halving alpha 2^-24, the smallest half-float subnormal, rounds
// it to 0 in the target, while colour 1000 times larger survives: rgb / 0 is infinite and the
// tint c / (1 + c) is NaN there. The alpha ramp's smallest alpha, 2^-16, halves exactly. Alpha
// is kept and colour is scaled by 0.8 to 1. (The suggested form, 1 / a stored in a half-float
// target, cannot be caught on lavapipe: it stores values beyond 65504 as 65504, not
// infinity.) Caught by: FINITE in inputs/subnormal only (alpha 2^-24 under colour 1000), and in
// a combined/* point drawn with subnormal inputs.
#include <acetate/effect.hpp>

class SubnormalAlpha final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.subnormal_alpha";
        e.display_name = "Harness: un-premultiplies a half-float copy";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.target("glow_source", 1);
        graph.pass({.name = "source",
                    .glsl = R"(
void main() {
    out_color = 0.5 * texelFetch(previous, ivec2(gl_FragCoord.xy), 0);  // alpha 2^-25 -> 0
}
)",
                    .inputs = {"previous"},
                    .output = "glow_source"});
        graph.pass({.name = "tint",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 prev = texelFetch(previous, p, 0);
    vec4 source = texelFetch(glow_source, p, 0);
    // "No colour, no coverage": not after the half-float rounding of a subnormal alpha.
    vec3 straight = any(greaterThan(source.rgb, vec3(0.0))) ? source.rgb / source.a : vec3(0.0);
    out_color = vec4(prev.rgb * (0.8 + 0.2 * straight / (1.0 + straight)), prev.a);
}
)",
                    .inputs = {"previous", "glow_source"}});
    }
};
ACETATE_REGISTER_EFFECT(SubnormalAlpha)
