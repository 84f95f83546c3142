// BROKEN on purpose: rule 1, premultiplied colour is never negative. A flare removal subtracts
// a black level of 0.15 (in straight colour, so 0.15 * a premultiplied) from every channel and
// does not clamp at 0, so any channel darker than 0.15 goes negative. Alpha is kept, colour
// stays 0 where a = 0 and the output is finite. (A level of 0.01 would never show: no synthetic
// input has a straight channel below 0.1, and on subnormal alpha the difference rounds to -0.)
// Caught by: the NON-NEGATIVE check only (in most cases: the standard inputs' colours dip to 0.1).
#include <acetate/effect.hpp>

class NegativeColour final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.negative_colour";
        e.display_name = "Harness: black level without a clamp";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "black_level",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb - 0.15 * prev.a, prev.a);  // no clamp at 0
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(NegativeColour)
