// The water's surface, made once at load: a tileable wave field and the caustic pattern that
// field focuses onto the bed.
//
// The height is a sum of sines whose wave vectors are whole cycles per tile, so the field tiles
// exactly (the shader samples it at two or three scales whose ratio is irrational, and scrolls
// each layer by a whole tile per period, so nothing repeats visibly and time wraps without a
// jump). The caustic density comes from tracing light through that surface: photons on a fine
// grid are displaced by the surface slope and splatted back onto the tile; where the surface
// focuses them the density rises above 1, where it spreads them it falls below. The mean is 1,
// so caustics move light around the bed rather than adding any.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace acetate::water {

inline constexpr int kWaveTexels = 256;  // one tile; the texture repeats row and column 0
inline constexpr float kMaxCausticDensity = 4.0f;

// A deterministic generator, so every machine builds the same texture.
class SplitMix64 {
  public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}
    double next_unit() {  // [0, 1)
        uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    }

  private:
    uint64_t state_;
};

// (kWaveTexels + 1)^2 texels of RGBA: slope d/dx, slope d/dy (largest slope length 1), height
// (largest magnitude 1), caustic density (mean 1, at most kMaxCausticDensity). Row and column
// kWaveTexels repeat row and column 0, so linear filtering wraps without a seam.
inline std::vector<float> build_wave_texture() {
    constexpr int n = kWaveTexels;
    constexpr double kTwoPi = 6.283185307179586;
    struct Wave {
        int kx, ky;
        double amplitude, phase;
    };
    std::vector<Wave> waves;
    SplitMix64 random(0x5eedf00dull);
    while (waves.size() < 24) {
        const double cycles = 2.0 + 10.0 * random.next_unit();
        const double angle = kTwoPi * random.next_unit();
        const Wave w{int(std::lround(cycles * std::cos(angle))),
                     int(std::lround(cycles * std::sin(angle))), 0.0, kTwoPi * random.next_unit()};
        if (w.kx == 0 && w.ky == 0) continue;
        waves.push_back(w);
        waves.back().amplitude = std::pow(std::hypot(w.kx, w.ky), -1.5);
    }
    std::vector<double> height(size_t(n) * n), sx(height.size()), sy(height.size());
    double max_height = 0, max_slope = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            double h = 0, dx = 0, dy = 0;
            for (const Wave& w : waves) {
                const double arg = kTwoPi * (w.kx * x + w.ky * y) / n + w.phase;
                h += w.amplitude * std::sin(arg);
                const double slope = w.amplitude * kTwoPi / n * std::cos(arg);
                dx += slope * w.kx;
                dy += slope * w.ky;
            }
            const size_t i = size_t(y) * n + x;
            height[i] = h, sx[i] = dx, sy[i] = dy;
            max_height = std::max(max_height, std::abs(h));
            max_slope = std::max(max_slope, std::hypot(dx, dy));
        }

    // Caustics: photons on a grid twice as fine, each pushed along the (normalised) slope by up
    // to kFocus texels, splatted bilinearly with wrap-around.
    constexpr double kFocus = 12.0;
    std::vector<double> photons(height.size(), 0.0);
    auto wrap = [](int v) { return ((v % n) + n) % n; };
    for (int j = 0; j < 2 * n; ++j)
        for (int i = 0; i < 2 * n; ++i) {
            const int x = i / 2, y = j / 2;  // the texel holding this photon
            const size_t t = size_t(y) * n + x;
            const double px = (i + 0.5) / 2 + kFocus * sx[t] / max_slope;
            const double py = (j + 0.5) / 2 + kFocus * sy[t] / max_slope;
            const double fx = px - 0.5, fy = py - 0.5;
            const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
            const double ax = fx - x0, ay = fy - y0;
            photons[size_t(wrap(y0)) * n + wrap(x0)] += (1 - ax) * (1 - ay);
            photons[size_t(wrap(y0)) * n + wrap(x0 + 1)] += ax * (1 - ay);
            photons[size_t(wrap(y0 + 1)) * n + wrap(x0)] += (1 - ax) * ay;
            photons[size_t(wrap(y0 + 1)) * n + wrap(x0 + 1)] += ax * ay;
        }
    // A 3x3 box takes the grid's speckle out; 4 photons land per texel on average.
    std::vector<double> density(photons.size());
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            double sum = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    sum += photons[size_t(wrap(y + dy)) * n + wrap(x + dx)];
            density[size_t(y) * n + x] = std::min(sum / (9.0 * 4.0), double(kMaxCausticDensity));
        }
    // The cap took a little light away: scale back to a mean of exactly 1 (then cap again).
    double mean = 0;
    for (double v : density) mean += v;
    mean /= double(density.size());
    for (double& v : density) v = std::min(v / mean, double(kMaxCausticDensity));

    std::vector<float> rgba(size_t(n + 1) * (n + 1) * 4);
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) {
            const size_t i = size_t(y % n) * n + x % n;
            float* out = &rgba[(size_t(y) * (n + 1) + x) * 4];
            out[0] = float(sx[i] / max_slope);
            out[1] = float(sy[i] / max_slope);
            out[2] = float(height[i] / max_height);
            out[3] = float(density[i]);
        }
    return rgba;
}

}  // namespace acetate::water
