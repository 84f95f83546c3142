#pragma once
// The camera as the renderer applies it: which part of the scene a frame shows and at what
// scale. Render pixel p of the output shows scene position origin + p / scale; everything the
// host plans in scene pixels (tiles, coverage, reach) is turned into render pixels here, in
// one place.

#include <cstdint>

#include "core/pixel_rect.hpp"

namespace acetate {

struct ViewTransform {
    double x = 0, y = 0;             // scene position of the output's top-left corner
    double scale = 1;                // render pixels per scene pixel
    uint32_t width = 0, height = 0;  // the output, in render pixels

    // The whole canvas at scale 1: what a scene renders without a camera.
    static ViewTransform whole(uint32_t canvas_width, uint32_t canvas_height) {
        return {0, 0, 1, canvas_width, canvas_height};
    }
    bool is_whole(uint32_t canvas_width, uint32_t canvas_height) const {
        return *this == whole(canvas_width, canvas_height);
    }
    // Scale 1 and a whole-pixel origin: every scene pixel lands on one render pixel, so a
    // tile drawn at its own size on whole scene pixels still maps texels to pixels.
    bool pixel_aligned() const;
    // The render pixels whose centres lie in the scene rect (x, y, w, h): what the rasterizer
    // shades for a quad over it, clipped to the output.
    PixelRect covered(double scene_x, double scene_y, double scene_w, double scene_h) const;
    // Every render pixel a rect of scene pixels touches, even in part, clipped to the output:
    // a conservative area for a scissor.
    PixelRect touched(const PixelRect& scene) const;
    bool operator==(const ViewTransform&) const = default;
};

}  // namespace acetate
