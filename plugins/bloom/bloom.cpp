// acetate.bloom -- a global effect: HDR bloom on the composite of all floors, in linear
// premultiplied light. Coverage-expanding: light spilling over transparent pixels raises their
// alpha (never lowers it).
//
// Passes, for L = levels (sizes are ceil(canvas / 2^k), the host's target sizing):
//   prefilter        previous -> down1        bright-pass (soft knee on max rgb, capped) and a
//                                             Karis-weighted 4x4 box: fireflies stay small
//   down2 .. downL   down(k-1) -> downk       4x4 box (4 bilinear taps)
//   up(L-1) .. up1   up(k+1) or downL, downk -> upk   9-tap tent of the coarser level + downk
//   composite        previous, up1 (down1 if L == 1) -> result
//                    rgb + intensity * up1 / L, alpha a + b (1 - a), b = min(1, max added rgb)
// The shaders say why each step is built the way it is.
//
// Presets trade speed for error against the widest (8-level) glow: fewer levels drop the widest
// part of the halo. Pixels shaded per frame at 1920x1080 (canvas 2,073,600 px): the composite
// writes every pixel, down passes shade levels 1..L, up passes levels 1..L-1:
//   low    (3 levels):  6 passes, 3,402,000 px (1.641 x canvas)
//   medium (4 levels):  8 passes, 3,442,560 px (1.660 x)
//   high   (5 levels): 10 passes, 3,452,760 px (1.665 x)
//   ultra  (6 levels): 12 passes, 3,455,310 px (1.666 x)
// Taps per pixel: composite 2, prefilter and down 4, up 10. The full-size composite and the two
// half-size level-1 passes are 90% of those pixels at every preset; levels past 3 add under 2%
// in pixels, so the presets differ mostly in passes (a draw and a barrier each) and in how wide
// the halo reaches, not in shading cost.

#include <acetate/effect.hpp>
#include <algorithm>
#include <string>

#include "bloom_shaders.hpp"

namespace {

using namespace acetate::sdk;

inline constexpr FloatParam kThreshold{
    "threshold", "linear light (max of r, g, b) where bloom starts", 1.0f, 0.0f, 16.0f};
inline constexpr FloatParam kKnee{
    "knee", "soft knee width as a fraction of the threshold (0 = hard)", 0.5f, 0.0f, 1.0f};
inline constexpr FloatParam kIntensity{
    "intensity", "how much of the bright-pass light is added back, spread", 0.6f, 0.0f, 4.0f};
// A quality knob the presets set, yet public: scenes and tests set it too (bloom_test.cpp).
inline constexpr IntParam kLevels{
    "levels", "depth of the mip chain: each level doubles the glow's reach", 5, 1, 8};
inline constexpr FloatParam kRadius{
    "radius", "upsample tent radius, in texels of the coarser level", 1.0f, 0.5f, 2.0f};

std::string down(int k) {
    return "down" + std::to_string(k);
}
std::string up(int k) {
    return "up" + std::to_string(k);
}

class Bloom final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "acetate.bloom";
        e.display_name = "Bloom";
        e.scope = ACETATE_SCOPE_GLOBAL;
        e.coverage = ACETATE_COVERAGE_EXPANDING;
        e.params = {kThreshold, kKnee, kIntensity, kLevels, kRadius};
        e.presets = quality_presets({{kLevels, {3, 4, 5, 6}}});
        return e;
    }

    void build(Graph& graph, const Floor& floor) const override {
        // The host hands an INT parameter over already rounded and clamped to its declared
        // range, [1, 8]; clamping again here is only a guard.
        const int levels = std::clamp(floor[kLevels], 1, 8);
        for (int k = 1; k <= levels; ++k) graph.target(down(k), 1u << k);
        for (int k = 1; k < levels; ++k) graph.target(up(k), 1u << k);

        // Each shader serves every level: input_names give its inputs the names it reads.
        graph.pass({.name = "prefilter",
                    .glsl = bloom_prefilter_frag,
                    .inputs = {"previous"},
                    .output = down(1),
                    .input_names = {"src"}});
        for (int k = 2; k <= levels; ++k)
            graph.pass({.name = down(k),
                        .glsl = bloom_down_frag,
                        .inputs = {down(k - 1)},
                        .output = down(k),
                        .input_names = {"src"}});
        // A pass cannot read and write one target, so each level gets its own upK.
        for (int k = levels - 1; k >= 1; --k) {
            const std::string coarser = k + 1 == levels ? down(levels) : up(k + 1);
            graph.pass({.name = up(k),
                        .glsl = bloom_up_frag,
                        .inputs = {coarser, down(k)},
                        .output = up(k),
                        .input_names = {"coarser", "level"}});
        }
        graph.pass({.name = "composite",
                    .glsl = bloom_composite_frag,
                    .inputs = {"previous", levels == 1 ? down(1) : up(1)},
                    .output = "result",
                    .defines = "#define LEVELS " + std::to_string(levels) + ".0\n",
                    .input_names = {"", "bloom"}});  // "": previous keeps its name
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(Bloom)
