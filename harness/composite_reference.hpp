#pragma once
// The integration `reference` check's model of the composite (docs/harness.md, `reference`):
// the floors' outputs blended with premultiplied "over" on the CPU, in double precision, as an
// RGBA16F target holds them after each blend. Past 65504 Vulkan lets the target hold either
// the maximum or infinity, and what a later blend makes of it differs (0.4 * 65504, or
// infinity), so each channel is followed under both behaviours and the GPU may match either.
// Pure functions of the floors' pixels, so the model is tested without a GPU.

#include <array>
#include <cstdint>
#include <vector>

#include "scene/image_io.hpp"

namespace acetate::harness {

// One channel of one pixel, under the two overflow behaviours.
struct ChannelReference {
    double saturated = 0;   // the target clamps to +-65504 (rounding toward zero does this)
    double overflowed = 0;  // it holds +-infinity; later blends follow IEEE (inf * 0 = NaN)
    // The largest finite magnitude each model held: one rounding is relative to it.
    double peak_saturated = 0, peak_overflowed = 0;
};

// One pixel of the composite after the floors blended so far.
struct PixelReference {
    std::array<ChannelReference, 4> channels;
    uint32_t blends = 0;  // floors blended at this pixel (the gate let them through)
};

// One RGBA16F rounding of a value whose blends peaked at `peak`: 2^-10 of it (one ULP, as
// Vulkan allows rounding toward zero as well as to nearest) plus 2^-24 for subnormals.
double half_rounding(double peak);

// Blends one floor's premultiplied output over the pixel: out + (1 - out.a) * pixel, then each
// model's overflow. Call it only where the host composites the floor (the caller gates).
void blend_over(PixelReference& pixel, const std::array<float, 4>& out);

// How far the GPU's value is from the model, in roundings of the pixel's peak: per channel the
// nearer of the two models, then the worst channel. A NaN or infinity on the GPU is 0 where
// the overflow model is NaN or infinity there (of the same sign, for two infinities), else
// infinite; a finite GPU value against a non-finite model counts only against the other model.
double roundings_off(const PixelReference& pixel, const std::array<float, 4>& gpu);

// ---- whole images -----------------------------------------------------------------------

// One floor as the compositor blends it: its output, and where the host lets it through (the
// stencil of its tiles, input alpha > 0; or for a floor with a coverage-expanding effect every
// output texel that is not exactly (0, 0, 0, 0)).
struct ReferenceFloor {
    const ImageRGBA* input = nullptr;
    const ImageRGBA* output = nullptr;
    bool expanding = false;
};

// The model after floors 0..count-1 over a transparent canvas (every image the same size).
std::vector<PixelReference> composite_reference(const std::vector<ReferenceFloor>& floors,
                                                size_t count);

// A composite against the model: the worst pixel in roundings and how many pixels are above
// the warn and fail thresholds.
struct ReferenceComparison {
    double worst = 0;
    uint32_t x = 0, y = 0;
    uint64_t warn_pixels = 0, fail_pixels = 0;
};
ReferenceComparison compare_to_reference(const std::vector<PixelReference>& reference,
                                         const ImageRGBA& composite, double warn_roundings,
                                         double fail_roundings);

// The model's saturated values, for the report's picture and examples (always finite).
ImageRGBA saturated_image(const std::vector<PixelReference>& reference, uint32_t width,
                          uint32_t height);

}  // namespace acetate::harness
