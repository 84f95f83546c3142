#include "core/pixel_rect.hpp"

#include <algorithm>
#include <cmath>

namespace acetate {

PixelRect pixels_covered(double x, double y, double w, double h, uint32_t width, uint32_t height) {
    // Pixel i is shaded when its centre i + 0.5 lies in [x, x + w) (Vulkan's top-left rule for
    // axis-aligned edges), i.e. i in [ceil(x - 0.5), ceil(x + w - 0.5)).
    PixelRect r;
    r.x0 = int64_t(std::ceil(x - 0.5));
    r.y0 = int64_t(std::ceil(y - 0.5));
    r.x1 = int64_t(std::ceil(x + w - 0.5));
    r.y1 = int64_t(std::ceil(y + h - 0.5));
    return intersect(r, PixelRect{0, 0, int64_t(width), int64_t(height)});
}

PixelRect intersect(const PixelRect& a, const PixelRect& b) {
    PixelRect r{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1),
                std::min(a.y1, b.y1)};
    return r.empty() ? PixelRect{} : r;
}

PixelRect bounding_union(const PixelRect& a, const PixelRect& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

bool covered_by_union(const PixelRect& target, const std::vector<PixelRect>& cover) {
    if (target.empty()) return true;
    // Split the target along every cover edge inside it; each resulting cell is either wholly
    // inside some cover rect or not. Scenes have few opaque tiles, so O(n^3) is fine.
    std::vector<int64_t> xs{target.x0, target.x1}, ys{target.y0, target.y1};
    for (const PixelRect& c : cover) {
        if (c.x0 > target.x0 && c.x0 < target.x1) xs.push_back(c.x0);
        if (c.x1 > target.x0 && c.x1 < target.x1) xs.push_back(c.x1);
        if (c.y0 > target.y0 && c.y0 < target.y1) ys.push_back(c.y0);
        if (c.y1 > target.y0 && c.y1 < target.y1) ys.push_back(c.y1);
    }
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    std::sort(ys.begin(), ys.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
        for (size_t j = 0; j + 1 < ys.size(); ++j) {
            const PixelRect cell{xs[i], ys[j], xs[i + 1], ys[j + 1]};
            const bool inside = std::any_of(cover.begin(), cover.end(), [&](const PixelRect& c) {
                return c.x0 <= cell.x0 && c.y0 <= cell.y0 && c.x1 >= cell.x1 && c.y1 >= cell.y1;
            });
            if (!inside) return false;
        }
    }
    return true;
}

std::vector<PixelRect> disjoint_union(const std::vector<PixelRect>& rects) {
    std::vector<int64_t> xs, ys;
    for (const PixelRect& r : rects)
        if (!r.empty()) {
            xs.insert(xs.end(), {r.x0, r.x1});
            ys.insert(ys.end(), {r.y0, r.y1});
        }
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    std::sort(ys.begin(), ys.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
    std::vector<PixelRect> out;
    std::vector<size_t> open;  // rects of `out` that end at the current band's top edge
    for (size_t j = 0; j + 1 < ys.size(); ++j) {
        std::vector<size_t> next;
        for (size_t i = 0; i + 1 < xs.size();) {
            auto covered = [&](size_t k) {
                const PixelRect cell{xs[k], ys[j], xs[k + 1], ys[j + 1]};
                return std::any_of(rects.begin(), rects.end(), [&](const PixelRect& r) {
                    return !r.empty() && r.x0 <= cell.x0 && cell.x1 <= r.x1 && r.y0 <= cell.y0 &&
                           cell.y1 <= r.y1;
                });
            };
            if (!covered(i)) {
                ++i;
                continue;
            }
            size_t end = i + 1;
            while (end + 1 < xs.size() && covered(end)) ++end;
            const PixelRect run{xs[i], ys[j], xs[end], ys[j + 1]};
            // The same x span directly above: grow that rect instead of starting one.
            auto above = std::find_if(open.begin(), open.end(), [&](size_t k) {
                return out[k].x0 == run.x0 && out[k].x1 == run.x1 && out[k].y1 == run.y0;
            });
            if (above != open.end()) {
                out[*above].y1 = run.y1;
                next.push_back(*above);
            } else {
                out.push_back(run);
                next.push_back(out.size() - 1);
            }
            i = end;
        }
        open = std::move(next);
    }
    return out;
}

uint64_t union_area(const std::vector<PixelRect>& rects) {
    uint64_t area = 0;
    for (const PixelRect& r : disjoint_union(rects)) area += r.area();
    return area;
}

}  // namespace acetate
