// The cost of acetate.water's load-time work on the CPU, per megapixel of mask: the exact
// distance transform at each cell size the presets use, and the wave texture (a fixed size).
// docs/performance.md records the figures; the transform is linear in cells, so ms per
// megapixel should hold across canvas sizes, which the two sizes here check.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "distance_field.hpp"
#include "wave_field.hpp"

namespace {

// A harbour-like mask: a sea along the bottom, a winding river and a pond (about 30% water).
std::vector<float> harbour_like_cover(int width, int height) {
    std::vector<float> cover(size_t(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double u = double(x) / width, v = double(y) / height;
            const bool sea = v > 0.72 + 0.06 * std::sin(u * 9.0);
            const bool river = std::abs(u - 0.78 - 0.04 * std::sin(v * 14.0)) < 0.025;
            const bool pond = std::hypot(u - 0.18, (v - 0.85) * 1.4) < 0.05;
            cover[size_t(y) * width + x] = sea || river || pond ? 1.0f : 0.0f;
        }
    return cover;
}

void BM_ShoreField(benchmark::State& state) {
    const int width = int(state.range(0)), height = int(state.range(1));
    const int divisor = int(state.range(2));
    const std::vector<float> cover = harbour_like_cover(width, height);
    for (auto _ : state)
        benchmark::DoNotOptimize(
            acetate::water::build_shore_field(cover, width, height, divisor).distance.data());
    state.counters["MP"] = double(width) * height / 1e6;  // ms per MP = Time / MP
}
BENCHMARK(BM_ShoreField)
    ->ArgNames({"w", "h", "divisor"})
    ->Args({1280, 720, 1})
    ->Args({1920, 1080, 1})
    ->Args({1920, 1080, 2})
    ->Args({1920, 1080, 4})
    ->Args({3840, 2160, 1})
    ->Unit(benchmark::kMillisecond);

void BM_WaveTexture(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(acetate::water::build_wave_texture().data());
}
BENCHMARK(BM_WaveTexture)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
