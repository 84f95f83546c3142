// acetate.fire -- a floor effect: flames, embers and smoke rising from the floor's `fire` mask,
// and the warm light they cast on what is around them. Coverage-EXPANDING: sparks and smoke
// rise past the floor's tiles. docs/plugins/fire.md describes the look, parameters and cost.
//
// Built at load (build() runs once per floor and load, so a floor switch builds nothing):
//   emitters      cells of the scene-space fire mask with fire in them (emitters.hpp)
//   particles     one instanced quad per particle slot: smoke, then flames, then embers, each
//                 quad the box that slot's particle can reach over a whole life, so the host
//                 shades only there; the quads' rects and each slot's emitter go in floor_data
//   texture.glow  the emitters blurred (R16F, one cell per 4 pixels): the light on the ground
// Passes: "glow" (previous lit by the glow -> result, over the floor's reach) and "particles"
// (the quads, premultiplied OVER onto result).
//
// Particles carry no state: each is a pure function of (seed, emitter, slot, time) through an
// integer hash (particles.frag), so any time renders directly, t = 0 is already alight, and the
// same time gives the same pixels. Time comes from one declared phase of kClockPeriod seconds,
// which every lifetime divides, so the fire loops seamlessly and stays smooth at 10^5 s.

#include <acetate/effect.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "emitters.hpp"
#include "fire_shaders.hpp"

namespace {

using namespace acetate::sdk;
using acetate::fire::Emitter;

inline constexpr FloatParam kIntensity{
    "intensity", "brightness of the flames' emission (HDR: above 1 is brighter than white)", 3.0f,
    0.0f, 64.0f};
inline constexpr FloatParam kTemperature{
    "temperature", "temperature of a new flame, kelvin: sets its blackbody colour", 1900.0f, 800.0f,
    3500.0f};
inline constexpr FloatParam kFlameHeight{
    "flame_height", "how far a flame rises over its life at full strength, scene pixels", 26.0f,
    2.0f, 256.0f};
inline constexpr FloatParam kFlameSize{
    "flame_size", "radius of a new flame particle at full strength, scene pixels", 5.0f, 0.5f,
    64.0f};
inline constexpr FloatParam kEmbers{"embers", "brightness of the embers (0 = none)", 1.0f, 0.0f,
                                    4.0f};
inline constexpr FloatParam kEmberSpeed{
    "ember_speed", "upward speed of an ember at birth, scene pixels per second", 45.0f, 0.0f,
    400.0f};
inline constexpr FloatParam kSmoke{"smoke", "opacity of the smoke (0 = none)", 0.35f, 0.0f, 1.0f};
inline constexpr FloatParam kSmokeHeight{
    "smoke_height", "how far smoke rises over its life, scene pixels", 90.0f, 0.0f, 1024.0f};
inline constexpr FloatParam kSmokeSize{
    "smoke_size", "radius of a new puff of smoke, scene pixels (it triples as it rises)", 7.0f,
    1.0f, 128.0f};
inline constexpr Vec2Param kWind{
    "wind", "wind, scene pixels per second (x right, y down)", {8.0f, 0.0f}, -200.0f, 200.0f};
inline constexpr FloatParam kIndoorWind{
    "indoor_wind", "wind left where the outdoors mask is 0 (1 = no damping)", 0.1f, 0.0f, 1.0f};
inline constexpr FloatParam kGlow{"glow", "how much the fire lights what is around it (0 = none)",
                                  0.5f, 0.0f, 4.0f};
inline constexpr FloatParam kGlowRadius{
    "glow_radius", "how far the fire's light reaches, scene pixels", 40.0f, 1.0f, 512.0f};
inline constexpr ColorParam kGlowColor{
    "glow_color", "colour of the fire's light", {1.0f, 0.55f, 0.25f}};
inline constexpr IntParam kSeed{"seed", "picks another fire of the same look", 1, 0, 65535};
// Cost knobs, set by the presets.
inline constexpr IntParam kFlames{.name = "flames_per_emitter",
                                  .description = "flame particles per emitter",
                                  .default_value = 5,
                                  .min_value = 1,
                                  .max_value = 16,
                                  .hidden = true};
inline constexpr IntParam kEmberCount{.name = "embers_per_emitter",
                                      .description = "ember particles per emitter",
                                      .default_value = 2,
                                      .min_value = 0,
                                      .max_value = 8,
                                      .hidden = true};
inline constexpr IntParam kPuffs{.name = "smoke_per_emitter",
                                 .description = "smoke particles per emitter",
                                 .default_value = 1,
                                 .min_value = 0,
                                 .max_value = 8,
                                 .hidden = true};
inline constexpr IntParam kSpacing{.name = "emitter_spacing",
                                   .description = "scene pixels between emitters",
                                   .default_value = 6,
                                   .min_value = 2,
                                   .max_value = 64,
                                   .hidden = true};

// The particle model's constants, handed to the shader as defines so there is one source.
// Every lifetime divides kClockPeriod, so the clock's wrap lands on a whole cycle of each.
inline constexpr double kClockPeriod = 2048.0;
inline constexpr double kLife[3] = {3.2, 0.8, 1.6};  // smoke, flame, ember (kind order)
inline constexpr double kGravity = 60.0;             // embers, scene pixels per second^2
inline constexpr int kGlowDivisor = 4;
inline constexpr size_t kMaxEmitters = 1024;

enum Kind { kSmokeKind = 0, kFlameKind = 1, kEmberKind = 2 };

std::string literal(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", v);
    std::string s = text;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

struct Box {
    float x0, y0, x1, y1;
};

// The box a particle of `kind` from emitter e can reach over any life (any random draw), with a
// pixel to spare: particles.frag keeps inside it by construction (the same bounds on each term).
Box reach_box(Kind kind, const Emitter& e, const Floor& floor, float wind_factor, int spacing) {
    const auto wind = floor[kWind];
    const double spread = spacing;  // a particle starts within +-spacing/2 of its emitter
    const double life = kLife[kind];
    // Wind moves a particle by wind * factor * time; smoke drifts 1.5 times as far.
    const double drift = (kind == kSmokeKind ? 1.5 : 1.0) * life * wind_factor;
    const double wx0 = std::min(0.0, wind[0] * drift), wx1 = std::max(0.0, wind[0] * drift);
    const double wy0 = std::min(0.0, wind[1] * drift), wy1 = std::max(0.0, wind[1] * drift);
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0, r = 0;
    if (kind == kFlameKind) {
        r = floor[kFlameSize] * std::sqrt(e.strength);
        const double sway = 0.3 * floor[kFlameSize];
        x0 = -0.5 * spread - sway, x1 = 0.5 * spread + sway;
        y0 = -0.25 * spread - floor[kFlameHeight] * e.strength, y1 = 0.25 * spread;
    } else if (kind == kSmokeKind) {
        r = 3.0 * floor[kSmokeSize];
        x0 = -0.5 * spread, x1 = 0.5 * spread;
        y0 = -0.25 * spread - floor[kFlameHeight] * e.strength - floor[kSmokeHeight];
        y1 = 0.25 * spread;
    } else {
        // Embers: vx in [-speed/2, speed/2], vy in [-speed, -speed/2], then gravity.
        r = 1.5;
        const double v = floor[kEmberSpeed];
        x0 = -0.5 * v * life, x1 = 0.5 * v * life;
        const double top_time = std::min(life, v / kGravity);  // highest point of the fastest
        y0 = -v * top_time + 0.5 * kGravity * top_time * top_time;
        y1 = std::max(0.0, -0.5 * v * life + 0.5 * kGravity * life * life);
    }
    return {float(e.x + x0 + wx0 - r - 1), float(e.y + y0 + wy0 - r - 1),
            float(e.x + x1 + wx1 + r + 1), float(e.y + y1 + wy1 + r + 1)};
}

class Fire final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "acetate.fire";
        e.display_name = "Fire";
        e.scope = ACETATE_SCOPE_FLOOR;
        e.coverage = ACETATE_COVERAGE_EXPANDING;
        e.masks = {"fire", "outdoors"};
        // Sparks smaller than a render pixel are drawn whole or not at all at scale 1/2 (the
        // rasterizer samples the pixel's centre), and their sums differ from any one scene
        // pixel's: the camera-scale relation measured 0.18 to 2.75 of the largest value nearby
        // over seeds 1-6. Drawing such sparks a render pixel wide at their area's brightness
        // would bring this down.
        e.scale_tolerance = 3.0f;
        e.params = {kIntensity,  kTemperature, kFlameHeight, kFlameSize, kEmbers,
                    kEmberSpeed, kSmoke,       kSmokeHeight, kSmokeSize, kWind,
                    kIndoorWind, kGlow,        kGlowRadius,  kGlowColor, kSeed,
                    kFlames,     kEmberCount,  kPuffs,       kSpacing};
        e.presets = quality_presets({{kFlames, {2, 3, 5, 8}},
                                     {kEmberCount, {1, 1, 2, 3}},
                                     {kPuffs, {0, 1, 1, 2}},
                                     {kSpacing, {10, 8, 6, 5}}});
        return e;
    }

    void build(Graph& graph, const Floor& floor) const override {
        if (floor.is_global() || !floor.has_mask("fire")) return;  // nothing: dropped
        const Mask fire = floor.mask("fire");
        const int width = int(fire.width), height = int(fire.height);
        std::vector<float> cover(size_t(width) * height), outdoors;
        for (size_t i = 0; i < cover.size(); ++i)
            cover[i] = std::clamp(fire.data[i * 4], 0.0f, 1.0f) *
                       std::clamp(fire.data[i * 4 + 3], 0.0f, 1.0f);
        if (floor.has_mask("outdoors")) {
            const Mask out = floor.mask("outdoors");
            outdoors.resize(cover.size());
            for (size_t i = 0; i < cover.size(); ++i)
                outdoors[i] = std::clamp(out.data[i * 4], 0.0f, 1.0f) *
                              std::clamp(out.data[i * 4 + 3], 0.0f, 1.0f);
        }
        // A mask with more fire than kMaxEmitters cells: wider cells, until it fits.
        // Fire is measured against the preset's cell, so wider cells keep thin fire alight.
        const int base = floor[kSpacing];
        int spacing = base;
        std::vector<Emitter> emitters;
        for (;; spacing *= 2) {
            emitters = acetate::fire::find_emitters(cover, outdoors, width, height, spacing, base);
            if (emitters.size() <= kMaxEmitters) break;
        }
        if (emitters.empty()) return;  // an empty fire mask: nothing to do

        const int counts[3] = {floor[kSmoke] > 0 ? floor[kPuffs] : 0, floor[kFlames],
                               floor[kEmbers] > 0 ? floor[kEmberCount] : 0};
        std::vector<float> rects, slots;
        const Bounds bounds = floor.coverage_bounds();
        double reach = 0;
        for (int kind = 0; kind < 3; ++kind)
            for (size_t i = 0; i < emitters.size(); ++i)
                for (int slot = 0; slot < counts[kind]; ++slot) {
                    const Emitter& e = emitters[i];
                    const float wind_factor = e.outdoor + (1 - e.outdoor) * floor[kIndoorWind];
                    const Box b = reach_box(Kind(kind), e, floor, wind_factor, spacing);
                    rects.insert(rects.end(), {b.x0, b.y0, b.x1 - b.x0, b.y1 - b.y0});
                    slots.insert(slots.end(), {e.x, e.y, e.strength, wind_factor, float(kind),
                                               float(slot), float(i), 0.0f});
                    reach = std::max({reach, bounds.x0 - double(b.x0), double(b.x1) - bounds.x1,
                                      bounds.y0 - double(b.y0), double(b.y1) - bounds.y1});
                }
        const uint32_t particles = uint32_t(rects.size() / 4);
        std::vector<float> data = rects;
        data.insert(data.end(), slots.begin(), slots.end());
        graph.floor_data(data);
        graph.reach(uint32_t(std::ceil(std::max(reach, 0.0))));

        const int cells_x = (width + kGlowDivisor - 1) / kGlowDivisor;
        const int cells_y = (height + kGlowDivisor - 1) / kGlowDivisor;
        graph.texture("glow", uint32_t(cells_x), uint32_t(cells_y),
                      acetate::fire::glow_map(emitters, cells_x, cells_y, kGlowDivisor,
                                              floor[kGlowRadius], spacing),
                      ACETATE_FORMAT_R16F);
        graph.phase("clock", kClockPeriod);
        graph.phase("flicker_a", 0.37);
        graph.phase("flicker_b", 0.53);
        graph.pass({.name = "glow", .glsl = glow_frag, .inputs = {"previous", "texture.glow"}});

        std::string defines = "#define PARAMS_OFFSET " + std::to_string(4 * particles) + "\n";
        defines += "#define CLOCK_PERIOD " + literal(kClockPeriod) + "\n";
        defines += "#define GRAVITY " + literal(kGravity) + "\n";
        const char* names[3] = {"SMOKE", "FLAME", "EMBER"};
        for (int kind = 0; kind < 3; ++kind)
            defines += std::string("#define ") + names[kind] + "_LIFE " + literal(kLife[kind]) +
                       "\n#define " + names[kind] + "_RATE " + literal(1.0 / kLife[kind]) +
                       "\n#define " + names[kind] + "_CYCLES " +
                       std::to_string(std::lround(kClockPeriod / kLife[kind])) + "\n";
        defines += "#define SPREAD " + literal(spacing) + "\n";
        graph.pass({.name = "particles",
                    .glsl = particles_frag,
                    .blend = ACETATE_BLEND_OVER,
                    .instance_count = particles,
                    .defines = defines});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(Fire)
