// acetate.lighting -- a floor effect: ambient light with a day/night level, the floor's own
// point lights from the scene, and a darkness level. Coverage-preserving.
//
// The lights come from the host's acetate_lights block (ABI 1.1), so build() has nothing to
// prepare: one pass, the same for every floor.

#include <acetate/effect.hpp>

#include "lighting_shaders.hpp"

namespace {

using namespace acetate::sdk;

inline constexpr FloatParam kDay{"day", "0 = night, 1 = full day: blends the two ambient levels",
                                 1.0f, 0.0f, 1.0f};
inline constexpr FloatParam kDayAmbient{"day_ambient", "ambient light level by day", 1.0f, 0.0f,
                                        2.0f};
inline constexpr FloatParam kNightAmbient{"night_ambient", "ambient light level by night", 0.15f,
                                          0.0f, 2.0f};
inline constexpr FloatParam kDarkness{
    "darkness", "dims ambient and point lights alike (0 = none, 1 = black)", 0.0f, 0.0f, 1.0f};
inline constexpr FloatParam kFlicker{"flicker", "how much point lights flicker with time", 0.0f,
                                     0.0f, 1.0f};
// A cost knob, not a look: only the presets set it (no scene or test ever did).
inline constexpr IntParam kMaxLights{.name = "max_lights",
                                     .description = "point lights considered per floor",
                                     .default_value = 16,
                                     .min_value = 0,
                                     .max_value = 64,
                                     .hidden = true};

class Lighting final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "acetate.lighting";
        e.display_name = "Lighting";
        e.scope = ACETATE_SCOPE_FLOOR;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {kDay, kDayAmbient, kNightAmbient, kDarkness, kFlicker, kMaxLights};
        e.presets = quality_presets({{kMaxLights, {4, 8, 16, 64}}});
        return e;
    }

    void build(Graph& graph, const Floor&) const override {
        graph.pass({.name = "light", .glsl = lighting_frag, .inputs = {"previous"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(Lighting)
