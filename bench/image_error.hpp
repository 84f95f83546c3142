#pragma once
// acetate-bench's error metrics: one rendered image against the reference configuration's, the
// heat map of where they differ, and the Pareto front of speed against error. Plain CPU code,
// so every number the reports print is checked by known answers without a GPU
// (tests/bench_metrics_test.cpp).

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "bench_results.hpp"
#include "core/result.hpp"
#include "scene/image_io.hpp"

namespace acetate::bench {

// The spacing of half floats (IEEE binary16) at `reference_value`: what one rounding of an
// rgba16f target can move a value there. 2^-24 for |r| < 2^-14 (the subnormals, evenly spaced);
// 2^(e-10) for |r| in [2^e, 2^(e+1)); 32 for |r| >= 65504 (the largest half, whose spacing
// continues past it rather than jumping to infinity). NaN for a NaN argument.
double half_spacing(double reference_value);

// The heat map's colour scale. A pixel's colour is its largest channel |test - reference| on a
// log10 scale from `floor_abs` (the first stop, near black; smaller differences and identical
// pixels also get it) to `ceiling_abs` (the last stop, pale yellow; larger ones also get it),
// through `stops` evenly spaced in log10 and interpolated linearly between neighbours in their
// sRGB encoding (a perceptual ramp: matplotlib's "inferno" sampled at 8 points, whose lightness
// rises steadily, so the order reads in grey too). A pixel with a NaN or infinity in the test
// image is `non_finite` (cyan, off the ramp). Exposed so the HTML can draw the same legend.
struct HeatMapScale {
    double floor_abs = 1e-6;
    double ceiling_abs = 1.0;
    std::array<std::array<uint8_t, 3>, 8> stops{};  // sRGB, from floor_abs to ceiling_abs
    std::array<uint8_t, 3> non_finite{};            // sRGB
};
const HeatMapScale& heat_map_scale();

// The heat-map colour of a pixel whose largest channel difference is `abs_difference`, as
// linear RGB: the image is linear light like every ImageRGBA, and save_image's sRGB encoding
// of a .png turns it back into exactly the scale's sRGB colours. A NaN or infinite difference
// gives `non_finite`.
std::array<float, 3> heat_map_colour(double abs_difference);

// Compares `test` against `reference` (premultiplied linear RGBA, every channel, alpha too) as
// ErrorStats defines, accumulating in double. The sizes must match (an error naming both
// otherwise). A NaN or infinity in `test` makes `finite` false, that channel's difference
// +infinity (so max_abs, max_roundings and mean_abs are +infinity and psnr_db -infinity, never
// NaN) and its pixel one over both thresholds. The reference must be finite: errors are
// measured against it, so a NaN there is a broken reference, reported as an error naming the
// pixel rather than hidden in the numbers. With `heat_map`, it receives an opaque image of the
// same size coloured by heat_map_colour().
Result<ErrorStats> compare_images(const ImageRGBA& test, const ImageRGBA& reference,
                                  const ErrorThresholds& thresholds, ImageRGBA* heat_map = nullptr);

// For each (cost, error) point, whether it is on the Pareto front: no other point has cost <=
// and error <= with at least one of them strictly less. Equal points do not dominate each
// other, so ties are all on the front. A point with a NaN coordinate is never on the front and
// dominates nothing.
std::vector<bool> pareto_front(const std::vector<std::pair<double, double>>& cost_error);

}  // namespace acetate::bench
