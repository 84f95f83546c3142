// CONTROL: breaks no rule. The expanding glow of expanding_glow.cpp (neighbours at +-2 pixels)
// with its reach declared honestly as 2 pixels, so the host shades only its floor's tiles grown
// by 2. The `reach` check must run and pass.
#include <acetate/effect.hpp>

#include "glow_shader.hpp"

namespace {

using namespace acetate::sdk;

inline constexpr FloatParam kStrength{"strength", "scales the neighbours' glow", 0.5f, 0.0f, 1.0f};

class DeclaredReach final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "test.harness.declared_reach";
        e.display_name = "Harness control: a glow with its reach declared";
        e.coverage = ACETATE_COVERAGE_EXPANDING;
        e.params = {kStrength};
        return e;
    }
    void build(Graph& graph, const Floor&) const override {
        graph.reach(2);
        graph.pass({.name = "glow", .glsl = kGlowShader, .inputs = {"previous"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(DeclaredReach)
