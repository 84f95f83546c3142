// acetate.specular -- a floor effect: physically based highlights (GGX distribution,
// height-correlated Smith visibility, Schlick Fresnel) from the floor's own point lights and
// sun, read through the floor's `specular`, `roughness` and `normal` masks. Coverage-preserving:
// the highlight is scaled by the pixel's alpha and alpha is written back untouched.
//
// Why it is built this way (docs/plugins/specular.md has the whole story): an earlier specular
// effect added its overlay without the pixel's alpha, so highlights leaked onto transparent
// pixels and, through them, onto the floor above; and its GGX barely showed, because a fixed
// sky colour was multiplied in, an unbounded intensity was clamped away and the mask was
// crushed by a pow. Here every term is the textbook one, every limit of it is bounded (the
// shader says how), and the only inputs are this floor's masks, lights and sun.
//
// One full-size pass, previous (+ masks) -> result, sampling every mask at gl_FragCoord in
// scene space, so tiles never seam. build() picks what the pass needs through defines: which
// masks the floor has, how many point lights (the preset's cap), whether there is a sun, the
// visibility term and the sparkle. When there is nothing to add (no specular mask, or no light
// and no sun) build() declares nothing and the host drops the instance.
//
// Cost: one pass over the floor's coverage bounds (at 1920x1080, at most 2,073,600 pixels),
// 1 to 3 mask taps and one GGX evaluation per light considered: low 4 lights, medium 16, high
// 32, ultra 64, plus the sun.

#include <acetate/effect.hpp>
#include <algorithm>
#include <string>
#include <vector>

#include "specular_shaders.hpp"

namespace {

using namespace acetate::sdk;

inline constexpr FloatParam kIntensity{
    "intensity", "scales every highlight (the specular mask's value times this)", 1.0f, 0.0f, 8.0f};
inline constexpr FloatParam kF0{
    "f0", "reflectance at normal incidence (Schlick's F0): 0.04 for most dielectrics, up to 1",
    0.04f, 0.0f, 1.0f};
inline constexpr FloatParam kRoughness{
    "roughness",
    "perceptual roughness where the floor's roughness mask is absent or transparent (0 = "
    "polished, clamped to 0.089; 1 = matte)",
    0.4f, 0.0f, 1.0f};
inline constexpr BoolParam kFlipY{
    "flip_y",
    "read the normal mask's green as pointing down the image (DirectX-style) instead of up", false};
inline constexpr FloatParam kSparkle{
    "sparkle", "micro-sparkle: how much each pixel's highlight glints, keeping its mean (0 = none)",
    0.0f, 0.0f, 1.0f};
inline constexpr IntParam kSparkleRate{"sparkle_rate", "sparkle patterns per second", 8, 1, 60};
// Cost knobs, not looks: only the presets set them.
inline constexpr IntParam kMaxLights{.name = "max_lights",
                                     .description =
                                         "point lights considered per floor (the "
                                         "first ones in scene order; the sun always)",
                                     .default_value = 32,
                                     .min_value = 1,
                                     .max_value = 64,
                                     .hidden = true};
inline constexpr BoolParam kSparkleEnabled{.name = "sparkle_enabled",
                                           .description = "whether the sparkle is computed at all",
                                           .default_value = true,
                                           .hidden = true};
inline constexpr BoolParam kExactVisibility{
    .name = "exact_visibility",
    .description = "the exact height-correlated Smith term (else its linear approximation)",
    .default_value = true,
    .hidden = true};

std::string define(const char* name, int value) {
    return std::string("#define ") + name + " " + std::to_string(value) + "\n";
}

class Specular final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "acetate.specular";
        e.display_name = "Specular";
        e.scope = ACETATE_SCOPE_FLOOR;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.masks = {"specular", "roughness", "normal"};
        e.params = {kIntensity,   kF0,        kRoughness,      kFlipY,          kSparkle,
                    kSparkleRate, kMaxLights, kSparkleEnabled, kExactVisibility};
        e.presets = quality_presets({{kMaxLights, {4, 16, 32, 64}},
                                     {kSparkleEnabled, {false, true, true, true}},
                                     {kExactVisibility, {false, false, true, true}}});
        return e;
    }

    void build(Graph& graph, const Floor& floor) const override {
        int points = 0;
        for (const AcetateLightInfo& l : floor.light_infos())
            if (l.kind == ACETATE_LIGHT_POINT) ++points;
        const bool sun = floor.sun().has_value();
        // The host rounds and clamps max_lights to [1, 64]; clamping again is only a guard.
        const int used = std::min(points, std::clamp(floor[kMaxLights], 1, 64));
        // Nothing can light this floor's highlights: declare nothing, and the host drops the
        // instance (the floor renders as if the effect were not listed: no pass, no copy).
        if (!floor.has_mask("specular") || (used == 0 && !sun)) return;
        const bool roughness = floor.has_mask("roughness"), normal = floor.has_mask("normal");
        std::vector<std::string> inputs = {"previous", "mask.specular"};
        if (roughness) inputs.push_back("mask.roughness");
        if (normal) inputs.push_back("mask.normal");
        // The sun, when there is one, is the floor's last light: acetate_lights[points].
        graph.pass({.name = "specular",
                    .glsl = specular_frag,
                    .inputs = inputs,
                    .defines = define("POINT_LIGHTS", used) +
                               define("SUN_INDEX", sun ? points : -1) +
                               define("HAS_ROUGHNESS_MASK", roughness) +
                               define("HAS_NORMAL_MASK", normal) +
                               define("EXACT_VISIBILITY", floor[kExactVisibility]) +
                               define("SPARKLE", floor[kSparkleEnabled])});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(Specular)
