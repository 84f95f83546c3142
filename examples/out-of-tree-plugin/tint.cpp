// com.example.tint: a floor effect that tints its floor's colour and keeps its alpha.
// Built against the installed Acetate SDK; see README.md.
#include <acetate/effect.hpp>

#include "tint_shaders.hpp"  // generated from tint.frag by acetate_add_effect()

namespace {

using namespace acetate::sdk;

class TintEffect final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo info;
        info.id = "com.example.tint";
        info.display_name = "Tint (example)";
        info.version_major = 1;
        info.scope = ACETATE_SCOPE_FLOOR;
        info.coverage = ACETATE_COVERAGE_PRESERVING;
        info.params = {
            {.name = "strength",
             .description = "How far the colour moves towards the tint: 0 leaves it unchanged.",
             .default_value = 0.5f,
             .min_value = 0.0f,
             .max_value = 1.0f},
            {.name = "r",
             .description = "Red factor of the tint (linear).",
             .default_value = 1.0f,
             .min_value = 0.0f,
             .max_value = 1.0f},
            {.name = "g",
             .description = "Green factor of the tint (linear).",
             .default_value = 0.8f,
             .min_value = 0.0f,
             .max_value = 1.0f},
            {.name = "b",
             .description = "Blue factor of the tint (linear).",
             .default_value = 0.55f,
             .min_value = 0.0f,
             .max_value = 1.0f},
        };
        info.presets = {
            {"low", {{"strength", 0.25f}}},
            {"medium", {{"strength", 0.5f}}},
            {"high", {{"strength", 0.75f}}},
            {"ultra", {{"strength", 1.0f}}},
        };
        return info;
    }

    // One fullscreen pass: previous -> result.
    void build(Graph& graph, const Floor&) const override {
        graph.pass({.name = "tint", .glsl = std::string(tint_frag), .inputs = {"previous"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(TintEffect)
