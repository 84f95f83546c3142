#pragma once
// Per-floor masks (docs/design.md, L-masks-per-floor and L-one-space): each floor's tiles may
// carry masks of several kinds; at load, all masks of one kind on one floor are composited into
// one scene-space image, so an effect samples one texture in the same space as everything else.
// A floor's masks are its own.

#include <filesystem>
#include <map>
#include <string>

#include "scene/image_io.hpp"
#include "scene/scene.hpp"

namespace acetate {

// Decoded mask images by path (each loaded once however many tiles name it).
using MaskImages = std::map<std::filesystem::path, ImageRGBA>;

// Composites `floor`'s masks of `kind` into a width x height scene-space image. Each mask is
// resampled bilinearly onto the pixels its tile's rect covers (pixel centres, as the
// rasterizer would), later tiles replacing earlier ones; pixels no such mask covers are 0.
ImageRGBA composite_floor_mask(const FloorDesc& floor, const std::string& kind, uint32_t width,
                               uint32_t height, const MaskImages& images);

// Bilinear sample of `image` at normalised (u, v), clamped to the edge, like the GPU sampler.
void sample_bilinear(const ImageRGBA& image, double u, double v, float out[4]);

}  // namespace acetate
