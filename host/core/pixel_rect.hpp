#pragma once
// Whole-pixel rectangles in scene space (origin top-left, y down) and the few set operations the
// planner needs.

#include <cstdint>
#include <vector>

namespace acetate {

// A half-open rectangle of whole pixels [x0, x1) x [y0, y1).
struct PixelRect {
    int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    uint64_t area() const { return empty() ? 0 : uint64_t(x1 - x0) * uint64_t(y1 - y0); }
    bool operator==(const PixelRect&) const = default;
};

// The pixels whose centres lie inside a scene rect (the pixels the rasterizer shades for a
// quad covering it), clipped to a canvas of width x height.
PixelRect pixels_covered(double x, double y, double w, double h, uint32_t width, uint32_t height);
PixelRect intersect(const PixelRect& a, const PixelRect& b);
PixelRect bounding_union(const PixelRect& a, const PixelRect& b);
// True when every pixel of `target` lies in at least one of `cover`.
bool covered_by_union(const PixelRect& target, const std::vector<PixelRect>& cover);
// The union of `rects` as rects that do not overlap, each pixel of the union in exactly one:
// bands between the rects' y edges, cut into runs between their x edges, and a run joined to
// the one above it when both span the same x (so one rect, or a row of rects, stays whole).
std::vector<PixelRect> disjoint_union(const std::vector<PixelRect>& rects);
// The exact number of pixels in the union of `rects`.
uint64_t union_area(const std::vector<PixelRect>& rects);

}  // namespace acetate
