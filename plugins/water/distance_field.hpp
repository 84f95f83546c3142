// The water's distance field, built once at load from the floor's water mask: for every water
// pixel, how far it is from the shore, in scene pixels.
//
// Exact Euclidean distance transform (Felzenszwalb and Huttenlocher, "Distance Transforms of
// Sampled Functions", 2012): the squared distance to the nearest land cell is the lower envelope
// of parabolas rooted at the land cells, found in one pass per row and one per column, so the
// cost is linear in the cells whatever the shape (measured in docs/performance.md). Squared
// distances are kept in double: at 16384 px they reach 5e8, past float's exact integers.
//
// Only the water's bounding box grown by one cell is transformed: every cell outside it is land,
// and the ring of land around the box is always at least as near as anything beyond it, so the
// result is exact. The canvas border is not land: a pond that runs off the canvas has no shore
// (and no foam) along the border.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace acetate::water {

// A box in cells, x1 and y1 exclusive.
struct CellBox {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
};

// The squared distance transform of one line: f holds 0 at land and +inf at water; d receives
// min over q of (p - q)^2 + f(q). v and z are scratch of n and n + 1 entries.
inline void distance_transform_line(const double* f, int n, double* d, int* v, double* z) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    int k = -1;  // index of the rightmost parabola in the envelope
    for (int q = 0; q < n; ++q) {
        if (f[q] == kInf) continue;  // no parabola rooted here
        double s = -kInf;
        while (k >= 0) {
            const int r = v[k];
            // Where the parabola from q meets the one from r (both finite).
            s = ((f[q] + double(q) * q) - (f[r] + double(r) * r)) / (2.0 * (q - r));
            if (s > z[k]) break;
            --k;
        }
        ++k;
        v[k] = q;
        z[k] = k == 0 ? -kInf : s;
        z[k + 1] = kInf;
    }
    if (k < 0) {  // no land on this line
        std::fill(d, d + n, kInf);
        return;
    }
    int j = 0;
    for (int q = 0; q < n; ++q) {
        while (z[j + 1] < q) ++j;
        const double dq = double(q) - v[j];
        d[q] = dq * dq + f[v[j]];
    }
}

// Squared Euclidean distance from each cell to the nearest land cell (land[i] true), row-major
// width x height; +inf where the grid holds no land at all. The first phase (each column's
// distance to its nearest land) is two sweeps in row order, so both phases walk memory in order
// and the cost stays linear on large canvases, not only in theory.
inline std::vector<double> squared_distance_to_land(std::span<const uint8_t> land, int width,
                                                    int height) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<double> grid(size_t(width) * height);
    for (int y = 0; y < height; ++y) {  // down: distance to the nearest land above or here
        double* row = &grid[size_t(y) * width];
        const uint8_t* here = &land[size_t(y) * width];
        for (int x = 0; x < width; ++x)
            row[x] = here[x] ? 0.0 : y > 0 ? row[x - width] + 1.0 : kInf;
    }
    for (int y = height - 2; y >= 0; --y) {  // up: or below
        double* row = &grid[size_t(y) * width];
        for (int x = 0; x < width; ++x) row[x] = std::min(row[x], row[x + width] + 1.0);
    }
    for (double& g : grid) g *= g;  // inf stays inf
    std::vector<double> d(width), z(width + 1);
    std::vector<int> v(width);
    for (int y = 0; y < height; ++y) {  // rows: the lower envelope of the columns' parabolas
        double* row = &grid[size_t(y) * width];
        distance_transform_line(row, width, d.data(), v.data(), z.data());
        std::copy(d.begin(), d.end(), row);
    }
    return grid;
}

// The water's distance field at one cell per `divisor` x `divisor` scene pixels.
struct ShoreField {
    CellBox box;                  // cells covered, in cell units of the canvas grid
    int divisor = 1;              // scene pixels per cell side
    std::vector<float> distance;  // per cell of box, row-major: scene px to the shore, 0 on land
    bool empty() const { return box.empty(); }
};

// The largest distance stored: the largest finite half float, so the texture holds it exactly.
inline constexpr float kFarFromShore = 65504.0f;

// `cover` is the water coverage per canvas pixel (0..1), width x height. A cell is water when
// the mean coverage of its pixels inside the canvas exceeds one half. Each water cell gets the
// distance from its centre to the nearest land cell's centre, minus half a cell: the distance to
// the edge between them (a water cell beside land reads half a cell). Land cells read 0. With
// no water at all the field is empty; with no land at all every cell reads kFarFromShore.
inline ShoreField build_shore_field(std::span<const float> cover, int width, int height,
                                    int divisor) {
    ShoreField field;
    field.divisor = std::max(1, divisor);
    const int d = field.divisor;
    const int cells_x = (width + d - 1) / d, cells_y = (height + d - 1) / d;
    std::vector<uint8_t> water(size_t(cells_x) * cells_y, 0);
    CellBox found{cells_x, cells_y, 0, 0};
    for (int cy = 0; cy < cells_y; ++cy)
        for (int cx = 0; cx < cells_x; ++cx) {
            double sum = 0;
            int count = 0;
            for (int y = cy * d; y < std::min(height, (cy + 1) * d); ++y)
                for (int x = cx * d; x < std::min(width, (cx + 1) * d); ++x, ++count)
                    sum += cover[size_t(y) * width + x];
            if (sum <= 0.5 * count) continue;
            water[size_t(cy) * cells_x + cx] = 1;
            found = {std::min(found.x0, cx), std::min(found.y0, cy), std::max(found.x1, cx + 1),
                     std::max(found.y1, cy + 1)};
        }
    if (found.empty()) return field;
    // Grown by one cell of land on every side the canvas has room for.
    field.box = {std::max(0, found.x0 - 1), std::max(0, found.y0 - 1),
                 std::min(cells_x, found.x1 + 1), std::min(cells_y, found.y1 + 1)};
    const int w = field.box.width(), h = field.box.height();
    std::vector<uint8_t> land(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            land[size_t(y) * w + x] = !water[size_t(y + field.box.y0) * cells_x + x + field.box.x0];
    const std::vector<double> squared = squared_distance_to_land(land, w, h);
    field.distance.resize(squared.size());
    for (size_t i = 0; i < squared.size(); ++i) {
        if (land[i]) continue;
        const double px = (std::sqrt(squared[i]) - 0.5) * d;  // +inf stays +inf
        field.distance[i] = float(std::min<double>(px, kFarFromShore));
    }
    return field;
}

}  // namespace acetate::water
