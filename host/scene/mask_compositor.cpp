#include "scene/mask_compositor.hpp"

#include <algorithm>
#include <cmath>

#include "core/pixel_rect.hpp"

namespace acetate {

void sample_bilinear(const ImageRGBA& image, double u, double v, float out[4]) {
    const double x = u * image.width - 0.5, y = v * image.height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double tx = x - fx, ty = y - fy;
    auto clamp_x = [&](double c) { return uint32_t(std::clamp(c, 0.0, double(image.width - 1))); };
    auto clamp_y = [&](double c) { return uint32_t(std::clamp(c, 0.0, double(image.height - 1))); };
    const uint32_t x0 = clamp_x(fx), x1 = clamp_x(fx + 1), y0 = clamp_y(fy), y1 = clamp_y(fy + 1);
    for (int c = 0; c < 4; ++c) {
        const double top = image.at(x0, y0)[c] * (1 - tx) + image.at(x1, y0)[c] * tx;
        const double bottom = image.at(x0, y1)[c] * (1 - tx) + image.at(x1, y1)[c] * tx;
        out[c] = float(top * (1 - ty) + bottom * ty);
    }
}

ImageRGBA composite_floor_mask(const FloorDesc& floor, const std::string& kind, uint32_t width,
                               uint32_t height, const MaskImages& images) {
    ImageRGBA out(width, height);
    for (const TileDesc& tile : floor.tiles) {
        const auto named = tile.masks.find(kind);
        if (named == tile.masks.end()) continue;
        const auto image = images.find(named->second);
        if (image == images.end()) continue;
        const PixelRect pixels = pixels_covered(tile.rect.x, tile.rect.y, tile.rect.width,
                                                tile.rect.height, width, height);
        for (int64_t y = pixels.y0; y < pixels.y1; ++y) {
            for (int64_t x = pixels.x0; x < pixels.x1; ++x) {
                const double u = (x + 0.5 - tile.rect.x) / tile.rect.width;
                const double v = (y + 0.5 - tile.rect.y) / tile.rect.height;
                sample_bilinear(image->second, u, v, out.at(uint32_t(x), uint32_t(y)));
            }
        }
    }
    return out;
}

}  // namespace acetate
