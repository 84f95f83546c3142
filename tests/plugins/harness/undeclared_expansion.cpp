// BROKEN on purpose: rule 2a, "coverage-preserving: out.a == in.a". The shader is exactly
// expanding_glow's (out = max(prev, strength * average of the neighbours at +-2 pixels)), so it
// raises alpha where it was 0 or low next to covered pixels, but the descriptor declares
// PRESERVING. Caught by: the COVERAGE check only (colour stays premultiplied, finite,
// deterministic, isolated; the parameter is connected).
#include <acetate/effect.hpp>

#include "glow_shader.hpp"

class UndeclaredExpansion final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.undeclared_expansion";
        e.display_name = "Harness: undeclared expansion";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;  // the lie: the shader grows alpha
        e.params = {{"strength", "scales the neighbours' glow", 0.5f, 0.0f, 1.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "glow", .glsl = kGlowShader, .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(UndeclaredExpansion)
