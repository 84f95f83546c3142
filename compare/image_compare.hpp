#pragma once
// One rendered image against a reference: the error in half-float roundings, mean, PSNR and the
// share of pixels over idiff-style thresholds, the heat map of where they differ, and the
// Pareto front of speed against error. acetate-bench compares presets with it, the harness
// compares a plugin's output with its blessed references. Plain CPU code, so every number is
// checked by known answers without a GPU (tests/unit/bench_metrics_test.cpp).

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/result.hpp"
#include "scene/image_io.hpp"

namespace acetate {

// idiff-style thresholds on a pixel's largest channel difference (absolute, linear light).
struct ErrorThresholds {
    // One half-float rounding at 1.0 (2^-10): below it, rgba16f cannot tell the images apart.
    double warn = 1.0 / 1024.0;
    // Four 8-bit steps at full scale (4/255): a difference a person can see on a display.
    double fail = 4.0 / 255.0;
};

struct ErrorStats {
    uint64_t pixels = 0;
    // Largest |test - reference| over pixels and channels, in units of the half-float spacing
    // at the reference value (2^-24 below 2^-14, the subnormals; 2^(e-10) for a value in
    // [2^e, 2^(e+1))). 0 when identical.
    double max_roundings = 0;
    double max_abs = 0;   // largest |test - reference|
    double mean_abs = 0;  // mean |test - reference| over every channel of every pixel
    // 10 log10(1 / MSE) with peak 1.0 (display white in linear light), over every channel;
    // infinite when the images are identical.
    double psnr_db = 0;
    double warn_share = 0;  // share of pixels whose largest channel difference > warn
    double fail_share = 0;  // ... > fail
    bool finite = true;     // no NaN or infinity in the test image
};

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

}  // namespace acetate
