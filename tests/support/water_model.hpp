#pragma once
// An independent CPU model of acetate.water's still-water look, in double: the exact distance to
// the shore by brute force (every water pixel against every land pixel, no transform), and the
// depth tint and murk as docs/plugins/water.md states them. The water tests compare the GPU
// against this, never against the shader run twice.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace acetate::test::water_model {

// Per pixel: the distance in scene pixels from the pixel's centre to the shore, that is to the
// nearest land pixel's centre minus half a pixel; 0 on land (cover <= 0.5). The canvas border
// is not land. +inf for water on a canvas without land.
inline std::vector<double> exact_shore_distance(const std::vector<double>& cover, int width,
                                                int height) {
    std::vector<std::array<int, 2>> land;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            if (cover[size_t(y) * width + x] <= 0.5) land.push_back({x, y});
    std::vector<double> distance(cover.size(), 0.0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (cover[size_t(y) * width + x] <= 0.5) continue;
            double best = std::numeric_limits<double>::infinity();
            for (const auto& [lx, ly] : land)
                best = std::min(best, std::hypot(double(x - lx), double(y - ly)));
            distance[size_t(y) * width + x] = best - 0.5;
        }
    return distance;
}

struct Tint {
    std::array<double, 3> shallow, deep, murk_color;
    double depth_range, murk, ambient;
};

// Still water, no lights: the bed (premultiplied rgb, alpha a) through the transmittance
// blended by depth = 1 - exp(-distance / depth_range), then the murk (its colour lit by the
// ambient level, times alpha) hiding it by murk * depth; mixed with the bed by the coverage.
inline std::array<double, 3> still_water(const std::array<double, 4>& bed, double cover,
                                         double distance, const Tint& t) {
    const double depth = std::isinf(distance) ? 1.0 : 1.0 - std::exp(-distance / t.depth_range);
    std::array<double, 3> out{};
    for (int c = 0; c < 3; ++c) {
        const double transmitted = bed[c] * (t.shallow[c] + (t.deep[c] - t.shallow[c]) * depth);
        const double murk = t.murk_color[c] * t.ambient * bed[3];
        const double water = transmitted + (murk - transmitted) * t.murk * depth;
        out[c] = bed[c] + (water - bed[c]) * cover;
    }
    return out;
}

// GLSL's smoothstep(0, 1, t) inverted on [0, 1] by bisection.
inline double inverse_smoothstep(double s) {
    double lo = 0, hi = 1;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (mid * mid * (3 - 2 * mid) < s ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace acetate::test::water_model
