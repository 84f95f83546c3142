// CONTROL: breaks no rule. Every harness check must pass. It grows alpha (a glow spreading past
// tile edges and into holes), which is allowed because it DECLARES itself coverage-expanding:
// out = max(prev, strength * average of the 4 neighbours at +-2 pixels), componentwise, so
// alpha never drops, and the neighbour term is a premultiplied average (rgb == 0 where a == 0).
// undeclared_expansion.cpp is the same shader declared preserving.
#include <acetate/effect.hpp>

#include "glow_shader.hpp"

class ExpandingGlow final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.expanding_glow";
        e.display_name = "Harness control: expanding glow";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_EXPANDING;
        e.params = {{"strength", "scales the neighbours' glow", 0.5f, 0.0f, 1.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "glow", .glsl = kGlowShader, .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(ExpandingGlow)
