#include "core/view_transform.hpp"

#include <algorithm>
#include <cmath>

namespace acetate {

bool ViewTransform::pixel_aligned() const {
    return scale == 1 && x == std::floor(x) && y == std::floor(y);
}

PixelRect ViewTransform::covered(double scene_x, double scene_y, double scene_w,
                                 double scene_h) const {
    return pixels_covered((scene_x - x) * scale, (scene_y - y) * scale, scene_w * scale,
                          scene_h * scale, width, height);
}

PixelRect ViewTransform::touched(const PixelRect& scene) const {
    if (scene.empty()) return {};
    const auto lower = [](double v) { return int64_t(std::floor(v)); };
    const auto upper = [](double v) { return int64_t(std::ceil(v)); };
    const PixelRect out{
        lower((double(scene.x0) - x) * scale), lower((double(scene.y0) - y) * scale),
        upper((double(scene.x1) - x) * scale), upper((double(scene.y1) - y) * scale)};
    return intersect(out, PixelRect{0, 0, int64_t(width), int64_t(height)});
}

}  // namespace acetate
