// com.example.tint: a floor effect that tints its floor's colour and keeps its alpha.
// Built against the installed Acetate SDK; see README.md.
#include <acetate/effect.hpp>

#include "tint_shaders.hpp"  // generated from tint.frag by acetate_add_effect()

namespace {

using namespace acetate::sdk;

// Each parameter is declared once; info() lists these constants, and presets name them.
inline constexpr FloatParam kStrength{
    "strength", "How far the colour moves towards the tint: 0 leaves it unchanged.", 0.5f, 0.0f,
    1.0f};
inline constexpr ColorParam kTint{"tint", "The tint (linear RGB).", {1.0f, 0.8f, 0.55f}};

class TintEffect final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo info;
        info.id = "com.example.tint";
        info.display_name = "Tint (example)";
        info.scope = ACETATE_SCOPE_FLOOR;
        info.coverage = ACETATE_COVERAGE_PRESERVING;
        info.params = {kStrength, kTint};
        info.presets = quality_presets({{kStrength, {0.25f, 0.5f, 0.75f, 1.0f}}});
        return info;
    }

    // One fullscreen pass: previous -> result.
    void build(Graph& graph, const Floor&) const override {
        graph.pass({.name = "tint", .glsl = tint_frag, .inputs = {"previous"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(TintEffect)
