#include "image_compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace acetate {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kLargestHalf = 65504.0;
constexpr double kSmallestNormalHalf = 0x1p-14;

}  // namespace

double half_spacing(double reference_value) {
    const double r = std::fabs(reference_value);
    if (std::isnan(r)) return std::numeric_limits<double>::quiet_NaN();
    if (r < kSmallestNormalHalf) return 0x1p-24;
    if (r >= kLargestHalf) return 32.0;
    // frexp: r = m * 2^exp with m in [0.5, 1), so r is in [2^(exp-1), 2^exp).
    int exp = 0;
    std::frexp(r, &exp);
    return std::ldexp(1.0, (exp - 1) - 10);
}

const HeatMapScale& heat_map_scale() {
    static const HeatMapScale scale = [] {
        HeatMapScale s;
        s.stops = {{{0x00, 0x00, 0x04},
                    {0x28, 0x0b, 0x54},
                    {0x65, 0x15, 0x6e},
                    {0x9f, 0x2a, 0x63},
                    {0xd4, 0x48, 0x42},
                    {0xf5, 0x7d, 0x15},
                    {0xfa, 0xc1, 0x27},
                    {0xfc, 0xff, 0xa4}}};
        s.non_finite = {0x00, 0xff, 0xff};
        return s;
    }();
    return scale;
}

std::array<float, 3> heat_map_colour(double abs_difference) {
    const HeatMapScale& scale = heat_map_scale();
    auto linear = [](const std::array<float, 3>& srgb) {
        return std::array<float, 3>{srgb_to_linear(srgb[0]), srgb_to_linear(srgb[1]),
                                    srgb_to_linear(srgb[2])};
    };
    if (!std::isfinite(abs_difference)) {
        const auto& c = scale.non_finite;
        return linear({c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f});
    }
    const double lo = std::log10(scale.floor_abs), hi = std::log10(scale.ceiling_abs);
    const double d = std::max(std::fabs(abs_difference), scale.floor_abs);
    const double t = std::clamp((std::log10(d) - lo) / (hi - lo), 0.0, 1.0);
    const double position = t * double(scale.stops.size() - 1);
    const size_t i = std::min(size_t(position), scale.stops.size() - 2);
    const double f = position - double(i);
    std::array<float, 3> srgb{};
    for (int c = 0; c < 3; ++c)
        srgb[c] = float((scale.stops[i][c] * (1.0 - f) + scale.stops[i + 1][c] * f) / 255.0);
    return linear(srgb);
}

Result<ErrorStats> compare_images(const ImageRGBA& test, const ImageRGBA& reference,
                                  const ErrorThresholds& thresholds, ImageRGBA* heat_map) {
    if (test.width != reference.width || test.height != reference.height)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("compare_images: the test image is {}x{} but the reference "
                                      "is {}x{}",
                                      test.width, test.height, reference.width, reference.height));
    const size_t pixels = size_t(test.width) * test.height;
    if (test.pixels.size() != pixels * 4 || reference.pixels.size() != pixels * 4)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("compare_images: a {}x{} image must hold {} floats, the "
                                      "test holds {} and the reference {}",
                                      test.width, test.height, pixels * 4, test.pixels.size(),
                                      reference.pixels.size()));

    ErrorStats stats;
    stats.pixels = pixels;
    if (heat_map) *heat_map = ImageRGBA(test.width, test.height);
    double sum_abs = 0, sum_squares = 0;
    uint64_t warned = 0, failed = 0;
    for (size_t p = 0; p < pixels; ++p) {
        double largest = 0;  // the pixel's largest channel difference
        for (size_t c = 0; c < 4; ++c) {
            const double t = test.pixels[p * 4 + c], r = reference.pixels[p * 4 + c];
            if (!std::isfinite(r))
                return make_error(
                    ErrorCode::InvalidInput,
                    fmt::format("compare_images: the reference has {} at pixel ({}, {}) channel "
                                "{}; errors cannot be measured against it",
                                r, p % test.width, p / test.width, "rgba"[c]));
            double d = kInfinity, roundings = kInfinity;
            if (std::isfinite(t)) {
                d = std::fabs(t - r);
                roundings = d / half_spacing(r);
            } else {
                stats.finite = false;
            }
            largest = std::max(largest, d);
            stats.max_abs = std::max(stats.max_abs, d);
            stats.max_roundings = std::max(stats.max_roundings, roundings);
            sum_abs += d;
            sum_squares += d * d;
        }
        warned += largest > thresholds.warn;
        failed += largest > thresholds.fail;
        if (heat_map) {
            const std::array<float, 3> colour = heat_map_colour(largest);
            float* out = &heat_map->pixels[p * 4];
            std::copy(colour.begin(), colour.end(), out);
            out[3] = 1.0f;
        }
    }
    if (pixels > 0) {
        const double channels = double(pixels) * 4.0;
        stats.mean_abs = sum_abs / channels;
        const double mse = sum_squares / channels;
        // 10 log10(1 / 0) is +infinity (identical), 10 log10(1 / inf) is -infinity (non-finite).
        stats.psnr_db = mse == 0 ? kInfinity : -10.0 * std::log10(mse);
        stats.warn_share = double(warned) / double(pixels);
        stats.fail_share = double(failed) / double(pixels);
    } else {
        stats.psnr_db = kInfinity;  // two empty images are identical
    }
    return stats;
}

std::vector<bool> pareto_front(const std::vector<std::pair<double, double>>& cost_error) {
    const size_t n = cost_error.size();
    auto has_nan = [](const std::pair<double, double>& p) {
        return std::isnan(p.first) || std::isnan(p.second);
    };
    std::vector<bool> front(n, false);
    // O(n^2): a plugin has a handful of presets and formats.
    for (size_t i = 0; i < n; ++i) {
        if (has_nan(cost_error[i])) continue;
        const auto [cost, error] = cost_error[i];
        bool dominated = false;
        for (size_t j = 0; j < n && !dominated; ++j) {
            if (j == i || has_nan(cost_error[j])) continue;
            const auto [other_cost, other_error] = cost_error[j];
            dominated = other_cost <= cost && other_error <= error &&
                        (other_cost < cost || other_error < error);
        }
        front[i] = !dominated;
    }
    return front;
}

}  // namespace acetate
