// acetate.fire's load-time work on the CPU: where the fire burns (emitters from the floor's
// fire mask, in scene space) and the warm light it casts on its surroundings (the glow map).
//
// The mask build() reads is the host's scene-space composite, so an emitter sits on the mask's
// scene pixels whatever the tile's offset or scale: there are no tile-local coordinates here to
// get wrong.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace acetate::fire {

struct Emitter {
    float x = 0, y = 0;  // scene pixels: the coverage-weighted centre of its cell
    float strength = 0;  // mean fire coverage over the cell, (0, 1]
    float outdoor = 1;   // the outdoors mask there (1 without one): scales the wind
};

// Cells of `spacing` scene pixels whose mean fire coverage is at least 1/20 become emitters,
// in row-major order. `cover` and `outdoors` are canvas-sized (outdoors may be empty).
inline std::vector<Emitter> find_emitters(std::span<const float> cover,
                                          std::span<const float> outdoors, int width, int height,
                                          int spacing) {
    std::vector<Emitter> out;
    const int s = std::max(1, spacing);
    for (int cy = 0; cy * s < height; ++cy)
        for (int cx = 0; cx * s < width; ++cx) {
            double sum = 0, sx = 0, sy = 0;
            int count = 0;
            for (int y = cy * s; y < std::min(height, (cy + 1) * s); ++y)
                for (int x = cx * s; x < std::min(width, (cx + 1) * s); ++x, ++count) {
                    const double c = cover[size_t(y) * width + x];
                    sum += c, sx += c * (x + 0.5), sy += c * (y + 0.5);
                }
            if (count == 0 || sum < 0.05 * count) continue;
            Emitter e{float(sx / sum), float(sy / sum), float(sum / count), 1.0f};
            if (!outdoors.empty()) {
                const int px = std::clamp(int(e.x), 0, width - 1);
                const int py = std::clamp(int(e.y), 0, height - 1);
                e.outdoor = std::clamp(outdoors[size_t(py) * width + px], 0.0f, 1.0f);
            }
            out.push_back(e);
        }
    return out;
}

// The glow: each emitter's strength splatted onto a grid of one cell per `divisor` pixels and
// blurred by a Gaussian of `radius` scene pixels (sigma = radius / 2), then scaled so its peak
// is 1. One float per cell, for an R16F texture. Separable, so linear in cells times radius.
inline std::vector<float> glow_map(const std::vector<Emitter>& emitters, int cells_x, int cells_y,
                                   int divisor, float radius) {
    std::vector<float> grid(size_t(cells_x) * cells_y, 0.0f);
    for (const Emitter& e : emitters) {
        const int x = std::clamp(int(e.x / divisor), 0, cells_x - 1);
        const int y = std::clamp(int(e.y / divisor), 0, cells_y - 1);
        grid[size_t(y) * cells_x + x] += e.strength;
    }
    const double sigma = std::max(0.5, double(radius) / 2.0 / divisor);
    const int reach = int(std::ceil(3 * sigma));
    std::vector<float> kernel(2 * reach + 1);
    for (int i = -reach; i <= reach; ++i)
        kernel[i + reach] = float(std::exp(-0.5 * (i * i) / (sigma * sigma)));
    auto blur = [&](bool along_x) {
        std::vector<float> out(grid.size(), 0.0f);
        for (int y = 0; y < cells_y; ++y)
            for (int x = 0; x < cells_x; ++x) {
                double sum = 0;
                for (int i = -reach; i <= reach; ++i) {
                    const int sx = along_x ? x + i : x, sy = along_x ? y : y + i;
                    if (sx < 0 || sy < 0 || sx >= cells_x || sy >= cells_y) continue;
                    sum += kernel[i + reach] * grid[size_t(sy) * cells_x + sx];
                }
                out[size_t(y) * cells_x + x] = float(sum);
            }
        grid.swap(out);
    };
    blur(true);
    blur(false);
    const float peak = *std::max_element(grid.begin(), grid.end());
    if (peak > 0)
        for (float& v : grid) v /= peak;
    return grid;
}

}  // namespace acetate::fire
