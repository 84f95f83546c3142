#include "composite_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace acetate::harness {
namespace {

constexpr double kHalfMax = 65504.0;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// As tests/gpu/composite_accuracy_test.cpp: one ULP of a half is 2^-10 of it, or 2^-24 below the
// smallest normal.
constexpr double kHalfRelative = 0x1p-10, kHalfAbsolute = 0x1p-24;

// A finite GPU value against one model's finite value, in roundings of the model's peak.
double distance(double model, float gpu, double peak) {
    if (!std::isfinite(model)) return kInfinity;
    return std::abs(model - double(gpu)) / half_rounding(peak);
}

double channel_off(const ChannelReference& c, float gpu) {
    if (!std::isfinite(gpu)) {
        // Only the overflow model lets the target hold a non-finite value. A NaN there (an
        // infinity times an opaque floor's 1 - a = 0) may be an infinity on the GPU when the
        // GPU overflowed a blend later than the model did (the model overflows early near the
        // maximum, see blend_over), so NaN and infinity are not told apart, only signs.
        if (std::isnan(c.overflowed)) return 0;
        if (std::isinf(c.overflowed))
            return std::isnan(gpu) || std::signbit(gpu) == std::signbit(c.overflowed) ? 0
                                                                                      : kInfinity;
        return kInfinity;
    }
    const double off = std::min(distance(c.saturated, gpu, c.peak_saturated),
                                distance(c.overflowed, gpu, c.peak_overflowed));
    return std::isnan(off) ? kInfinity : off;  // a NaN in a floor's output reached the model
}

// Where the host blends floor `f` at pixel `i`: the stencil of its tiles, or for a floor with
// a coverage-expanding effect wherever its output is not exactly (0, 0, 0, 0) (the composite
// shader discards those; -0 compares equal to 0 there as here).
bool composited_at(const ReferenceFloor& f, size_t i) {
    const float* out = &f.output->pixels[i * 4];
    if (f.expanding) return out[0] != 0 || out[1] != 0 || out[2] != 0 || out[3] != 0;
    return f.input->pixels[i * 4 + 3] > 0.0f;
}

}  // namespace

double half_rounding(double peak) {
    return kHalfRelative * peak + kHalfAbsolute;
}

void blend_over(PixelReference& pixel, const std::array<float, 4>& out) {
    const double keep = 1.0 - double(out[3]);
    for (int ch = 0; ch < 4; ++ch) {
        ChannelReference& c = pixel.channels[ch];
        // Saturating: clamping never widens an error (it is 1-Lipschitz), so one rounding per
        // blend of the clamped values' peak still bounds a correct GPU.
        c.saturated = std::clamp(out[ch] + keep * c.saturated, -kHalfMax, kHalfMax);
        c.peak_saturated = std::max(c.peak_saturated, std::abs(c.saturated));
        // Overflowing: the GPU's value before this blend's rounding may already be off by one
        // rounding per earlier blend, so it may overflow where the exact value stays just below
        // 65504; the model overflows there too. Where the GPU does not overflow, the
        // saturating model covers what it holds. Once infinite, IEEE arithmetic carries it:
        // another blend keeps it (1 - a > 0) or makes it NaN (a = 1), as blending hardware does.
        double v = out[ch] + keep * c.overflowed;
        const double allowance = pixel.blends * half_rounding(c.peak_overflowed);
        if (std::isfinite(v) && std::abs(v) > kHalfMax - allowance)
            v = std::copysign(kInfinity, v);
        else if (std::isfinite(v))
            c.peak_overflowed = std::max(c.peak_overflowed, std::abs(v));
        c.overflowed = v;
    }
    ++pixel.blends;
}

double roundings_off(const PixelReference& pixel, const std::array<float, 4>& gpu) {
    double worst = 0;
    for (int ch = 0; ch < 4; ++ch)
        worst = std::max(worst, channel_off(pixel.channels[ch], gpu[ch]));
    return worst;
}

std::vector<PixelReference> composite_reference(const std::vector<ReferenceFloor>& floors,
                                                size_t count) {
    if (floors.empty()) return {};
    const size_t pixels = floors[0].output->pixels.size() / 4;
    std::vector<PixelReference> reference(pixels);
    for (size_t f = 0; f < std::min(count, floors.size()); ++f)
        for (size_t i = 0; i < pixels; ++i) {
            if (!composited_at(floors[f], i)) continue;
            const float* out = &floors[f].output->pixels[i * 4];
            blend_over(reference[i], {out[0], out[1], out[2], out[3]});
        }
    return reference;
}

ReferenceComparison compare_to_reference(const std::vector<PixelReference>& reference,
                                         const ImageRGBA& composite, double warn_roundings,
                                         double fail_roundings) {
    ReferenceComparison result;
    for (uint32_t y = 0; y < composite.height; ++y)
        for (uint32_t x = 0; x < composite.width; ++x) {
            const float* g = composite.at(x, y);
            const double off =
                roundings_off(reference[size_t(y) * composite.width + x], {g[0], g[1], g[2], g[3]});
            if (off > warn_roundings) ++result.warn_pixels;
            if (off > fail_roundings) ++result.fail_pixels;
            if (off > result.worst) {
                result.worst = off;
                result.x = x;
                result.y = y;
            }
        }
    return result;
}

ImageRGBA saturated_image(const std::vector<PixelReference>& reference, uint32_t width,
                          uint32_t height) {
    ImageRGBA image(width, height);
    for (size_t i = 0; i < reference.size() && i * 4 < image.pixels.size(); ++i)
        for (int ch = 0; ch < 4; ++ch)
            image.pixels[i * 4 + ch] = float(reference[i].channels[ch].saturated);
    return image;
}

}  // namespace acetate::harness
