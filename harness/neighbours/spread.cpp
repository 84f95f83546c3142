// The harness's neighbour (docs/harness.md, "Contexts"): the context cases place it before and
// after the plugin under test on its floor (or among the global effects), as hosts place other
// effects. Built twice from this file: as a floor effect and as a global one
// (ACETATE_SPREAD_GLOBAL).
//
// A coverage-expanding glow: the input, or an eighth of the sum of the four pixels 3 away where
// that is larger, componentwise. So it puts alpha past the floor's tiles and its coverage
// bounds, which a plugin after it is given and must keep. It keeps the contract (alpha never
// drops, rgb stays 0 where a is 0) and has no parameter: the contexts vary the plugin, not it.
#include <acetate/effect.hpp>

namespace {

using namespace acetate::sdk;

constexpr const char* kShader = R"(
vec4 tap(ivec2 p) {
    return texelFetch(previous, clamp(p, ivec2(0), ivec2(acetate_canvas.xy) - 1), 0);
}
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 around = 0.125 * (tap(p + ivec2(3, 0)) + tap(p - ivec2(3, 0)) +
                           tap(p + ivec2(0, 3)) + tap(p - ivec2(0, 3)));
    out_color = max(texelFetch(previous, p, 0), around);
}
)";

class Spread final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = ACETATE_SPREAD_ID;
        e.display_name = "Harness neighbour: spread";
        e.coverage = ACETATE_COVERAGE_EXPANDING;
#ifdef ACETATE_SPREAD_GLOBAL
        e.scope = ACETATE_SCOPE_GLOBAL;
#endif
        return e;
    }
    void build(Graph& graph, const Floor&) const override {
#ifndef ACETATE_SPREAD_GLOBAL
        graph.reach(3);  // shaded only within the floor's tiles grown by 3 pixels
#endif
        graph.pass({.name = "spread", .glsl = kShader, .inputs = {"previous"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(Spread)
