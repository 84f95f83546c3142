// acetate.bloom -- a global effect: HDR bloom on the composite of all floors, in linear
// premultiplied light. Coverage-expanding: light spilling over transparent pixels raises their
// alpha (never lowers it).
//
// Passes, for the chain's levels F = first_level .. L = levels (sizes are ceil(canvas / 2^k), the
// host's target sizing):
//   prefilter        previous -> downF        bright-pass (soft knee on max rgb, capped) and a
//                                             Karis-weighted box (4x4 taps at F = 1 and 2, 8x8
//                                             at F = 3): fireflies stay small
//   down(F+1)..downL down(k-1) -> downk       4x4 box (4 bilinear taps)
//   up(L-1) .. upF   up(k+1) or downL, downk -> upk   9-tap tent of the coarser level + downk
//                                             (one bilinear tap at upF when fine_tent is off)
//   composite        previous, upF (downF if L == F) -> result
//                    rgb + intensity * upF / (L - F + 1), alpha a + b (1 - a),
//                    b = min(1, max added rgb)
// The shaders say why each step is built the way it is.
//
// Presets trade speed for error against ultra; all four reach level 6 (the same halo width) and
// differ in how fine the glow's core is, which is where the cost is. Pixels shaded per frame at
// 1920x1080 (canvas 2,073,600 px; the composite writes every pixel, down passes shade levels
// F..L, up passes F..L-1):
//   low    (levels 3..6):              8 passes, 2,159,310 px (1.041 x canvas)
//   medium (levels 2..6):             10 passes, 2,418,510 px (1.166 x)
//   high   (levels 1..6, one-tap up1): 12 passes, 3,455,310 px (1.666 x), up1 1 tap instead of 9
//   ultra  (levels 1..6):             12 passes, 3,455,310 px (1.666 x)
// The full-size composite costs the same at every preset; the half-size prefilter and up1 are
// most of the rest, hence the ladder: drop up1's tent (high), then the half-size level
// (medium), then the quarter-size one (low). docs/performance.md measures each step's saving and
// error.

#include <acetate/effect.hpp>
#include <algorithm>
#include <cmath>
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
// The chain's finest level: 1 = half, 2 = quarter, 3 = eighth size. Starting at 2 skips the two
// half-size passes (the prefilter's and the finest upsample's), most of bloom's cost, and loses
// the glow's tightest ring. Quality knobs the presets set, like levels and fine_tent.
inline constexpr IntParam kFirstLevel{
    "first_level",
    "finest level of the mip chain: 1 = half, 2 = quarter, 3 = eighth size (cheaper, softer core)",
    1, 1, 3};
inline constexpr BoolParam kFineTent{
    "fine_tent", "the finest upsample uses the 9-tap tent (off: one bilinear tap, cheaper)", true};
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
        e.params = {kThreshold, kKnee, kIntensity, kLevels, kRadius, kFirstLevel, kFineTent};
        e.presets = quality_presets({{kFirstLevel, {3, 2, 1, 1}},
                                     {kLevels, {6, 6, 6, 6}},
                                     {kFineTent, {true, true, false, true}}});
        return e;
    }

    void build(Graph& graph, const Floor& floor) const override {
        // The host hands an INT parameter over already rounded and clamped to its declared
        // range; clamping again here is only a guard. The chain runs from level `first` to
        // level `last` (at least one level).
        // Under a camera the chain moves by the scale's power of two, so the halo keeps its
        // width in scene pixels: at scale 2 each level is half as many scene pixels, and one
        // level more reaches as far (ABI 1.2; scale 1 without a camera).
        const int shift = int(std::lround(std::log2(double(floor.render_scale()))));
        const int first = std::clamp(floor[kFirstLevel] + shift, 1, 3);
        const int last = std::clamp(floor[kLevels] + shift, first, 8);
        for (int k = first; k <= last; ++k) graph.target(down(k), 1u << k);
        for (int k = first; k < last; ++k) graph.target(up(k), 1u << k);

        // Each shader serves every level: input_names give its inputs the names it reads.
        graph.pass({.name = "prefilter",
                    .glsl = bloom_prefilter_frag,
                    .inputs = {"previous"},
                    .output = down(first),
                    .defines = "#define DIVISOR " + std::to_string(1 << first) +
                               ".0\n#define TAPS " + std::to_string(std::max(2, (1 << first) / 2)) +
                               "\n",
                    .input_names = {"src"}});
        for (int k = first + 1; k <= last; ++k)
            graph.pass({.name = down(k),
                        .glsl = bloom_down_frag,
                        .inputs = {down(k - 1)},
                        .output = down(k),
                        .input_names = {"src"}});
        // A pass cannot read and write one target, so each level gets its own upK.
        for (int k = last - 1; k >= first; --k) {
            const std::string coarser = k + 1 == last ? down(last) : up(k + 1);
            const bool one_tap = k == first && !floor[kFineTent];
            graph.pass({.name = up(k),
                        .glsl = bloom_up_frag,
                        .inputs = {coarser, down(k)},
                        .output = up(k),
                        .defines = one_tap ? "#define ONE_TAP\n" : "",
                        .input_names = {"coarser", "level"}});
        }
        graph.pass({.name = "composite",
                    .glsl = bloom_composite_frag,
                    .inputs = {"previous", last == first ? down(first) : up(first)},
                    .output = "result",
                    .defines = "#define LEVELS " + std::to_string(last - first + 1) +
                               ".0\n#define SCALE " + std::to_string(1 << first) + ".0\n",
                    .input_names = {"", "bloom"}});  // "": previous keeps its name
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(Bloom)
