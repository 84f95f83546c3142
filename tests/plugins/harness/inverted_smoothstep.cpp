// BROKEN on purpose: a result GLSL leaves undefined. It fades colour as coverage grows with
// smoothstep(1.0, 0.0, a), a falling ramp written with the edges swapped; GLSL leaves
// smoothstep undefined for edge0 >= edge1. llvmpipe computes the falling ramp the author
// expected, so every image looks right here; another driver may not. Colour is scaled by 0.8
// to 1 and alpha is kept. Caught by: the UNDEFINED-RESULTS check only (in every contract case,
// rendered once more with a checked smoothstep that returns NaN for inverted edges).
#include <acetate/effect.hpp>

class InvertedSmoothstep final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.inverted_smoothstep";
        e.display_name = "Harness: smoothstep with inverted edges";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "fade",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float fade = smoothstep(1.0, 0.0, prev.a);  // 1 at a = 0, 0 at a = 1: undefined in GLSL
    out_color = vec4(prev.rgb * (0.8 + 0.2 * fade), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(InvertedSmoothstep)
