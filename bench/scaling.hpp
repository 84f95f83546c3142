#pragma once
// acetate-bench --scaling (docs/performance.md): frame time and pixels shaded against the number
// of floors, the number of effects per floor and the canvas size, on generated layered scenes,
// with a least-squares cost model frame_ms ≈ fixed + a × pixels_shaded + b × passes and how far
// each point is from it.
//
// The series (each point a scene written as JSON + EXR tiles into a temporary folder and read
// back with parse_scene_file; the top floor active, so every floor is composited; rgba16f
// targets, the plugins' defaults, t = 2.5 s; the median of the timed frames after one warm-up):
//   floors   1, 2, 4, 8, 16 at 1920×1080 with 1 effect per floor;
//   effects  0..5 per floor at 1920×1080 with 4 floors;
//   canvas   1280×720, 1920×1080, 2560×1440, 3840×2160 with 4 floors and 1 effect.
// The effects, in the order a floor lists them: acetate.lighting, acetate.specular,
// acetate.water, acetate.fire, a second acetate.lighting (scaling_effect_plugins()).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_runner.hpp"
#include "core/result.hpp"

namespace acetate {
class Renderer;
}

namespace acetate::bench {

struct ScalingPoint {
    std::string series;  // "floors", "effects", "canvas"
    uint32_t width = 0, height = 0, floors = 0, effects_per_floor = 0;
    double median_ms = 0, min_ms = 0, max_ms = 0;  // wall clock per frame (record+submit+wait)
    uint64_t pixels_shaded = 0;                    // FrameStats::pixels_shaded of a frame
    uint32_t passes = 0;                           // FrameStats::passes (draws recorded)
    double model_ms = 0;                           // the cost model's prediction
    double residual = 0;                           // (median - model) / model
    uint32_t frames = 0;                           // timed frames behind the median
    double load_ms = 0;                            // Compositor::load
    double other_round_ms = 0;  // the median of the round not kept (0 with one round)
};

struct CostModel {
    double fixed_ms = 0;
    double ns_per_pixel = 0;  // = ms per megapixel shaded
    double ms_per_pass = 0;   // 0 when passes was dropped from the fit
    double r_squared = 0;
    std::string formula;  // the fitted line with its units, and how it was fitted
    // Extra, for the reader.
    bool passes_dropped = false;  // the per-pass term was not significant (|t| < 2) or unsolvable
    double passes_t = 0;          // its t statistic in the 3-parameter fit (0 when unsolvable)
    uint32_t fitted_points = 0;   // distinct configurations the fit used
};

struct ScalingResults {
    std::vector<ScalingPoint> points;  // series floors, then effects, then canvas
    CostModel model;
    std::string load_before, load_after;  // /proc/loadavg: the machine is shared
};

struct ScalingOptions {
    uint32_t frames = 9;
    bool quick = false;  // quick: tiny canvases and fewer points, for ctest
};

// A configuration that appears in two series (4 floors, 1 effect, 1920×1080 is in all three) is
// measured once and listed in each. The full study goes over every configuration twice (two
// rounds, a fresh load each) and keeps the round with the lower median: the machine is shared,
// and contention only ever adds time. Each round times `frames` frames after one warm-up, but
// no more than fit in 4 s by the warm-up frame's time (at least 3): the whole run stays near
// three minutes on lavapipe. Quick: one round. Errors name the point (a scene that does not
// load, a frame that fails).
Result<ScalingResults> run_scaling(Renderer& renderer, const ScalingOptions& options,
                                   const ProgressFn& progress);

// One table per series (point, passes, pixels shaded, median ms (min–max), model ms, residual
// %), the model with its units and R², and one sentence on the worst point.
std::string scaling_markdown(const ScalingResults& results);

// ---- pieces, exposed for the tests --------------------------------------------------------

// Fits frame_ms ≈ fixed + a × pixels_shaded + b × passes by ordinary least squares over `points`
// (their median_ms; 3×3 normal equations, pixels in megapixels for conditioning). The per-pass
// term is dropped (and the 2-parameter fit kept) when its t statistic is under 2 in magnitude,
// when passes do not vary independently of pixels, or with fewer than 4 points; the formula
// says so. With fewer than 2 points, or no variation at all, the model is the mean.
CostModel fit_cost_model(const std::vector<ScalingPoint>& points);

// The model's frame time for a point.
double predict_ms(const CostModel& model, uint64_t pixels_shaded, uint32_t passes);

// Fills model_ms and residual of every point from `model`.
void apply_cost_model(const CostModel& model, std::vector<ScalingPoint>& points);

// The plugin ids of effects 1..5 of a floor, in order.
const std::vector<std::string>& scaling_effect_plugins();

// Writes the tile images and masks every scaling scene shares into `dir` (float EXR): three
// tiles of `texture_width` × 3/4 of it, premultiplied, with feathered alpha edges; a `specular`
// mask on each, a `water` mask on the first, a `fire` mask (three small spots) on the second.
Result<void> write_scaling_assets(const std::filesystem::path& dir, uint32_t texture_width);

// Writes `dir`/`name` (acetate-scene/1 JSON over the assets in `dir`): `floors` floors of three
// partly overlapping tiles covering about 60% of a width × height canvas each (shifted a little
// from floor to floor), four lights and a sun per floor, the first `effects_per_floor` of
// scaling_effect_plugins() on every floor, the top floor active.
Result<std::filesystem::path> write_scaling_scene(const std::filesystem::path& dir,
                                                  const std::string& name, uint32_t width,
                                                  uint32_t height, uint32_t floors,
                                                  uint32_t effects_per_floor);

// The share of the canvas the tiles of floor `floor` of such a scene cover (their union).
double scaling_floor_coverage(uint32_t width, uint32_t height, uint32_t floor);

}  // namespace acetate::bench
