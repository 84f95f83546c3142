// A coverage-expanding effect that grows its floor by one pixel (a 3x3 maximum), for the reach
// test: with `declare_reach` it tells the host so (set_reach(1)), and the host may then shade
// only the floor's tiles grown by one pixel instead of the whole canvas. Same image either way.
#include <acetate/effect.hpp>

namespace {

using namespace acetate::sdk;

inline constexpr BoolParam kDeclareReach{"declare_reach", "Declare a reach of 1 pixel.", true};

class ReachGlow final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "test.reach_glow";
        e.coverage = ACETATE_COVERAGE_EXPANDING;
        e.params = {kDeclareReach};
        return e;
    }
    void build(Graph& graph, const Floor& floor) const override {
        if (floor[kDeclareReach]) graph.reach(1);
        graph.pass({.name = "grow",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy), last = ivec2(acetate_canvas.xy) - 1;
    vec4 best = vec4(0.0);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            vec4 c = texelFetch(previous, clamp(p + ivec2(dx, dy), ivec2(0), last), 0);
            if (c.a > best.a) best = c;
        }
    out_color = best;
}
)",
                    .inputs = {"previous"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(ReachGlow)
