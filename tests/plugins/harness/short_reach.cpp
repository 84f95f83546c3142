// BREAKS: "a declared reach is a promise" (docs/contract.md, 2b); caught by `reach`. The glow
// of expanding_glow.cpp (neighbours at +-2 pixels) declares a reach of 1 pixel: the host shades
// its floor's tiles grown by 1, and the glow 2 pixels out is cut off. Shaded over the whole
// canvas, the floor differs there.
#include <acetate/effect.hpp>

#include "glow_shader.hpp"

namespace {

using namespace acetate::sdk;

inline constexpr FloatParam kStrength{"strength", "scales the neighbours' glow", 0.5f, 0.0f, 1.0f};

class ShortReach final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "test.harness.short_reach";
        e.display_name = "Harness control: a reach declared too short";
        e.coverage = ACETATE_COVERAGE_EXPANDING;
        e.params = {kStrength};
        return e;
    }
    void build(Graph& graph, const Floor&) const override {
        graph.reach(1);  // the glow reaches 2
        graph.pass({.name = "glow", .glsl = kGlowShader, .inputs = {"previous"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(ShortReach)
