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

// Cells of `spacing` scene pixels holding at least 1/20 of a full `base` x `base` cell of fire
// become emitters, in row-major order; strength is the fire per pixel, counting at most
// base x base pixels, so cells wider than the base (a mask with too much fire) keep a thin
// line alight and as strong. `cover` and `outdoors` are canvas-sized (outdoors may be empty).
inline std::vector<Emitter> find_emitters(std::span<const float> cover,
                                          std::span<const float> outdoors, int width, int height,
                                          int spacing, int base) {
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
            const double full = std::min<double>(count, double(base) * base);
            if (count == 0 || sum < 0.05 * full) continue;
            Emitter e{float(sx / sum), float(sy / sum), float(std::min(1.0, sum / full)), 1.0f};
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
// blurred by a Gaussian of `radius` scene pixels (sigma = radius / 2, at least 2 px; cut at
// 3 sigma), then divided by a fixed reference: the centre of a full-strength fire filling a
// disc of radius / 4 with emitters every `spacing` pixels reads 1. Light adds up, so a bigger
// fire glows more, capped at 4; a fire elsewhere on the floor changes nothing here. One float
// per cell, for an R16F texture. Separable, so linear in cells times radius.
inline std::vector<float> glow_map(const std::vector<Emitter>& emitters, int cells_x, int cells_y,
                                   int divisor, float radius, int spacing) {
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
    // The reference, in the blur's units (a splatted emitter peaks at 1): emitters 1/spacing^2
    // per px^2 under a Gaussian of sigma px over a disc of radius R gives
    // 2 pi sigma^2 / spacing^2 * (1 - exp(-R^2 / (2 sigma^2))).
    const double sigma_px = sigma * divisor, disc = radius / 4.0;
    const double reference =
        std::max(1.0, 2 * 3.141592653589793 * sigma_px * sigma_px / (double(spacing) * spacing) *
                          (1 - std::exp(-disc * disc / (2 * sigma_px * sigma_px))));
    for (float& v : grid) v = float(std::min(4.0, v / reference));
    return grid;
}

}  // namespace acetate::fire
