// com.example.colour_grade: lift, gamma, gain and saturation on its floor's colour, alpha kept.
// Built against the installed Acetate SDK; see README.md.
#include <acetate/effect.hpp>

#include "colour_grade_shaders.hpp"  // generated from colour_grade.frag by acetate_add_effect()

namespace {

using namespace acetate::sdk;

// Lift and gain are colours (what black and white become); gamma is a plain vector per channel.
inline constexpr ColorParam kLift{
    "lift", "What black becomes (linear RGB).", {0.0f, 0.0f, 0.0f}, 0.0f, 0.5f};
inline constexpr Vec3Param kGamma{
    "gamma", "Per channel: above 1 brightens the midtones.", {1.0f, 1.0f, 1.0f}, 0.25f, 4.0f};
inline constexpr ColorParam kGain{
    "gain", "What white becomes (linear RGB).", {1.0f, 1.0f, 1.0f}, 0.0f, 2.0f};
inline constexpr FloatParam kSaturation{"saturation", "0 is grey, 1 leaves colours as they are.",
                                        1.0f, 0.0f, 2.0f};

class ColourGrade final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo info;
        info.id = "com.example.colour_grade";
        info.display_name = "Colour grade (example)";
        info.scope = ACETATE_SCOPE_FLOOR;
        info.coverage = ACETATE_COVERAGE_PRESERVING;
        info.params = {kLift, kGamma, kGain, kSaturation};
        return info;  // no presets: a grade is a look, with no cost to trade
    }

    void build(Graph& graph, const Floor&) const override {
        graph.pass({.name = "grade", .glsl = colour_grade_frag, .inputs = {"previous"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(ColourGrade)
