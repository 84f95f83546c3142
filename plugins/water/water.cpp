// acetate.water -- a floor effect: the water of the floor's `water` mask, seen from above.
// Coverage-preserving. docs/plugins/water.md describes the look, the parameters and the cost.
//
// What is built at load, once per floor that has water (build() runs once per floor per load,
// so a floor switch builds nothing and the first frame does no CPU work):
//   texture.shore   the distance from each water pixel to the shore (distance_field.hpp),
//                   covering only the water's bounding box, at one cell per field_divisor
//                   pixels, in R16F
//   texture.waves   the tileable wave field and its caustic pattern (wave_field.hpp)
// and one pass over the floor, which shades water and copies everything else. A floor without
// water, or whose water mask is empty, declares nothing: the host skips the instance, so the
// floor costs no pass, no texture and no shader.
//
// Animation runs on phases (fract(time / period), computed in double by the host): each wave
// layer scrolls one whole tile per period, so the pattern is as smooth at 10^5 s as at 1 s and
// the same time always gives the same pixels.

#include <acetate/effect.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "distance_field.hpp"
#include "water_shaders.hpp"
#include "wave_field.hpp"

namespace {

using namespace acetate::sdk;
using acetate::water::build_shore_field;
using acetate::water::build_wave_texture;
using acetate::water::kWaveTexels;
using acetate::water::ShoreField;

// Colour: transmittance of the water column (how much of the bed's light gets through).
inline constexpr ColorParam kShallowColor{
    "shallow_color", "transmittance at the shore (per channel, 0..1)", {0.85f, 0.97f, 0.95f}};
inline constexpr ColorParam kDeepColor{
    "deep_color", "transmittance at full depth (per channel, 0..1)", {0.25f, 0.50f, 0.55f}};
inline constexpr ColorParam kMurkColor{
    "murk_color", "albedo of the silt and algae suspended in the water", {0.10f, 0.30f, 0.32f}};
inline constexpr FloatParam kDepthRange{
    "depth_range", "scene pixels from the shore to 63% of full depth", 48.0f, 1.0f, 1024.0f};
inline constexpr FloatParam kDepthFromMask{
    "depth_from_mask", "0: depth from the distance to the shore, 1: from the mask's value", 0.0f,
    0.0f, 1.0f};
inline constexpr FloatParam kMurk{"murk", "how much suspended silt hides the bed at full depth",
                                  0.5f, 0.0f, 1.0f};
// Surface.
inline constexpr FloatParam kWaves{
    "waves", "wave height: scales refraction and the tilt the glints see (0 = still)", 1.0f, 0.0f,
    4.0f};
inline constexpr FloatParam kRefraction{
    "refraction", "largest refraction offset at waves = 1, scene pixels", 3.0f, 0.0f, 32.0f};
inline constexpr FloatParam kWaveScale{
    "wave_scale", "size of the wave pattern's tile, scene pixels", 160.0f, 16.0f, 2048.0f};
inline constexpr FloatParam kWaveSpeed{
    "wave_speed", "how fast the waves travel, scene pixels per second", 10.0f, 0.0f, 512.0f};
inline constexpr FloatParam kIndoorWaves{
    "indoor_waves", "waves left where the outdoors mask is 0 (1 = no damping)", 0.15f, 0.0f, 1.0f};
// Light.
inline constexpr FloatParam kCaustics{
    "caustics", "strength of the caustic light on the bed (0 = none)", 0.6f, 0.0f, 1.0f};
inline constexpr FloatParam kFoam{"foam", "opacity of the shore foam (0 = none)", 0.7f, 0.0f, 1.0f};
inline constexpr FloatParam kFoamWidth{
    "foam_width", "width of the foam band along the shore, scene pixels", 6.0f, 0.0f, 128.0f};
inline constexpr FloatParam kFoamBreakup{
    "foam_breakup", "how much moving gaps break the foam band (0 = solid)", 0.6f, 0.0f, 1.0f};
inline constexpr ColorParam kFoamColor{"foam_color", "albedo of the foam", {0.9f, 0.95f, 0.95f}};
inline constexpr FloatParam kAmbient{
    "ambient", "light on the murk and the foam besides the floor's lights and sun", 0.5f, 0.0f,
    4.0f};
inline constexpr FloatParam kGlints{"glints", "strength of the lights' and sun's highlights", 1.0f,
                                    0.0f, 4.0f};
inline constexpr FloatParam kRoughness{
    "roughness", "perceptual roughness of the surface for the glints", 0.15f, 0.0f, 1.0f};
// Cost knobs, set by the presets.
inline constexpr IntParam kTaps{.name = "taps",
                                .description = "refraction taps per water pixel (4 texels each)",
                                .default_value = 4,
                                .min_value = 1,
                                .max_value = 16,
                                .hidden = true};
inline constexpr IntParam kCausticOctaves{.name = "caustic_octaves",
                                          .description = "caustic layers at irrational scales",
                                          .default_value = 2,
                                          .min_value = 1,
                                          .max_value = 3,
                                          .hidden = true};
inline constexpr IntParam kFieldDivisor{
    .name = "field_divisor",
    .description = "scene pixels per distance-field cell side (1, 2 or 4)",
    .default_value = 1,
    .min_value = 1,
    .max_value = 4,
    .hidden = true};
inline constexpr IntParam kMaxLights{.name = "max_lights",
                                     .description = "point lights considered for glints and foam",
                                     .default_value = 16,
                                     .min_value = 0,
                                     .max_value = 64,
                                     .hidden = true};

// The second and third wave layers' scales relative to the first: irrational, so the layers'
// tiles never line up (the golden ratio's inverse and its square).
inline constexpr double kLayerScale[3] = {1.0, 0.6180339887498949, 0.3819660112501051};

std::string float_literal(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", v);
    std::string s = text;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

class Water final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "acetate.water";
        e.display_name = "Water";
        e.scope = ACETATE_SCOPE_FLOOR;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.masks = {"water", "outdoors"};
        // At scale 1/2 the refraction bends neighbours averaged over 2x2 scene pixels and the
        // glints see normals from a coarser wave field: the harness's camera-scale relation
        // measured 0.022 to 0.118 of the largest value nearby over seeds 1-6; twice the worst.
        e.scale_tolerance = 0.25f;
        e.params = {kShallowColor,   kDeepColor,    kDepthRange, kDepthFromMask, kMurk,
                    kMurkColor,      kWaves,        kRefraction, kWaveScale,     kWaveSpeed,
                    kIndoorWaves,    kCaustics,     kFoam,       kFoamWidth,     kFoamBreakup,
                    kFoamColor,      kAmbient,      kGlints,     kRoughness,     kTaps,
                    kCausticOctaves, kFieldDivisor, kMaxLights};
        e.presets = quality_presets({{kTaps, {1, 2, 6, 8}},
                                     {kCausticOctaves, {1, 2, 3, 3}},
                                     {kFieldDivisor, {4, 2, 1, 1}},
                                     {kMaxLights, {4, 8, 16, 64}}});
        return e;
    }

    void build(Graph& graph, const Floor& floor) const override {
        if (floor.is_global() || !floor.has_mask("water")) return;  // nothing: skipped
        const Mask mask = floor.mask("water");
        const int width = int(mask.width), height = int(mask.height);
        // Coverage: a one-channel mask's grey (r) times its alpha (0 where no tile carries it).
        std::vector<float> cover(size_t(width) * height);
        for (size_t i = 0; i < cover.size(); ++i)
            cover[i] = std::clamp(mask.data[i * 4], 0.0f, 1.0f) *
                       std::clamp(mask.data[i * 4 + 3], 0.0f, 1.0f);
        // The box of every pixel with any water: outside it the pass copies without a lookup.
        int x0 = width, y0 = height, x1 = 0, y1 = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                if (cover[size_t(y) * width + x] > 0.0f)
                    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x + 1),
                    y1 = std::max(y1, y + 1);
        if (x1 <= x0) return;  // the mask holds no water: nothing to do

        const int requested = floor[kFieldDivisor];
        const int divisor = requested >= 4 ? 4 : requested >= 2 ? 2 : 1;
        const ShoreField shore = build_shore_field(cover, width, height, divisor);
        // Water that is nowhere more than half covering has no inside, so no distance: a 1x1
        // field of 0 (all shore) serves it.
        const int field_w = shore.empty() ? 1 : shore.box.width();
        const int field_h = shore.empty() ? 1 : shore.box.height();
        // One channel of half floats: exact near the shore (1/1024 px under 1 px, 1/64 px at
        // 16 px), where foam and refraction need it, and 2 bytes a cell.
        std::vector<float> distance = shore.distance;
        if (distance.empty()) distance.assign(1, 0.0f);
        graph.texture("shore", uint32_t(field_w), uint32_t(field_h), distance, ACETATE_FORMAT_R16F);
        // The same for every floor and load: made once per process (immutable after that).
        static const std::vector<float> waves = build_wave_texture();
        graph.texture("waves", kWaveTexels + 1, kWaveTexels + 1, waves);

        // Each layer moves one whole tile (its size along its direction) per period.
        const double speed = floor[kWaveSpeed];
        const bool animate = speed > 0.0;
        for (int layer = 0; layer < 3; ++layer) {
            const double tile = floor[kWaveScale] * kLayerScale[layer];
            const double along = layer == 2 ? std::sqrt(2.0) : 1.0;  // layer 2 moves diagonally
            graph.phase("wave" + std::to_string(layer),
                        animate ? tile * along / (speed * (1.0 - 0.15 * layer)) : 1.0);
        }
        // The foam's gaps drift at half the waves' speed across a tile half layer 2's size.
        const double foam_tile = 0.5 * floor[kWaveScale] * kLayerScale[2];
        graph.phase("foam", animate ? foam_tile * std::sqrt(2.0) / (0.5 * speed) : 1.0);

        const bool outdoors = floor.has_mask("outdoors");
        std::vector<std::string> inputs = {"previous", "mask.water", "texture.shore",
                                           "texture.waves"};
        if (outdoors) inputs.push_back("mask.outdoors");
        std::string defines;
        defines += "#define TAPS " + std::to_string(std::clamp(floor[kTaps], 1, 16)) + "\n";
        defines += "#define CAUSTIC_OCTAVES " +
                   std::to_string(std::clamp(floor[kCausticOctaves], 1, 3)) + "\n";
        defines +=
            "#define MAX_LIGHTS " + std::to_string(std::clamp(floor[kMaxLights], 0, 64)) + "\n";
        defines += "#define HAS_OUTDOORS " + std::string(outdoors ? "1" : "0") + "\n";
        defines += "#define ANIMATE " + std::string(animate ? "1.0" : "0.0") + "\n";
        defines += "#define FIELD_DIVISOR " + float_literal(shore.divisor) + "\n";
        defines += "#define FIELD_ORIGIN vec2(" + float_literal(shore.box.x0) + ", " +
                   float_literal(shore.box.y0) + ")\n";
        // The water's box in scene pixels: outside it a pixel is copied without a texture read.
        defines += "#define WATER_BOX vec4(" + float_literal(x0) + ", " + float_literal(y0) + ", " +
                   float_literal(x1) + ", " + float_literal(y1) + ")\n";
        for (int layer = 0; layer < 3; ++layer)
            defines += "#define LAYER" + std::to_string(layer) + "_SCALE " +
                       float_literal(floor[kWaveScale] * kLayerScale[layer]) + "\n";
        defines += "#define FOAM_SCALE " + float_literal(foam_tile) + "\n";
        graph.pass({.name = "water", .glsl = water_frag, .inputs = inputs, .defines = defines});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(Water)
