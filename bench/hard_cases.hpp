#pragma once
// acetate-bench --hard-cases: the stability table (docs/performance.md). Every shipped plugin on
// scenes built to hit the edges of half precision and of the frame's geometry: alpha down to
// 2^-24 (the smallest half subnormal), colour at 65504 (the largest half), 16 floors, a 1x1
// canvas, odd sizes (37x23, 1x517) and time 10^5 s. Each case is rendered at the plugin's
// defaults (no preset) with rgba16f targets and again with rgba32f targets; the rgba16f image
// must be finite, keep the premultiplied contract (rgb 0 where alpha is 0, alpha never
// negative) and stay within the plugin's stated tolerance of the rgba32f one.

#include <filesystem>
#include <string>
#include <vector>

#include "bench_runner.hpp"
#include "core/result.hpp"
#include "scene/scene.hpp"

namespace acetate {
class Renderer;
}

namespace acetate::bench {

struct HardCaseResult {
    std::string plugin;     // e.g. "acetate.water"
    std::string hard_case;  // one of hard_case_names()
    bool finite = true;     // no NaN or infinity anywhere in the rgba16f output
    bool contract = true;   // rgba16f output: rgb == 0 wherever a == 0, a never negative
    // The largest error of the rgba16f render against the rgba32f render of the same case, in
    // the unit hard_case_roundings() defines (infinite when not finite).
    double max_roundings = 0;
    double tolerance = 0;  // the stated tolerance in the same unit, with `why`
    std::string why;       // the tolerance's reason, one line
    bool pass = false;     // finite && contract && max_roundings <= tolerance
    std::string note;      // anything a reader must know
    // Extra, for the reader: compare_images' max_roundings (the spacing at the reference value
    // alone) and the level the unit was taken at least at (0: the reference value alone).
    double roundings_at_reference = 0;
    double level = 0;
};

// The cases, in table order: "alpha 2^-24", "colour 65504", "16 floors", "1x1", "odd 37x23",
// "odd 1x517", "time 1e5 s".
const std::vector<std::string>& hard_case_names();

// The five shipped plugins, in table order.
const std::vector<std::string>& shipped_plugins();

// Renders every case for each plugin id in `plugins` (empty: all five shipped) on `renderer`.
// An unknown plugin id, a scene that does not load or a broken reference is an error; a case
// that renders but fails its checks is a result with pass = false.
Result<std::vector<HardCaseResult>> run_hard_cases(Renderer& renderer,
                                                   const std::vector<std::string>& plugins,
                                                   const ProgressFn& progress);

// The markdown table: one row per plugin, one column per case; a cell is "✓ 0.50" (pass, max
// roundings), "✗ 3.1" (over tolerance), "✗ NaN/inf" (not finite) or "✗ contract", with
// notes as footnotes; then a legend of the unit and of each plugin's tolerance and why.
std::string hard_cases_markdown(const std::vector<HardCaseResult>& results);

// ---- pieces, exposed for the tests --------------------------------------------------------

// The error unit of the table, per channel: |test - reference| / half_spacing(max(|reference|,
// level)), i.e. half-float roundings at the reference value, or at `level` where that is larger.
// `level` is 0 for pointwise effects (each output is computed once from exact inputs and
// rounded once), and the case's peak input level for effects that sum many stored values (a
// blur): a pixel whose reference is near 0 beside large ones carries the rounding of the
// large values it was summed from. Returns the largest over every channel of every pixel;
// +infinity for a NaN or infinity in `test`. The sizes must match.
double hard_case_roundings(const ImageRGBA& test, const ImageRGBA& reference, double level);

// Whether `image` keeps the premultiplied contract (rgb == 0 where a == 0, a >= 0); `where`
// receives the first pixel that does not, as "(x, y) rgba".
bool keeps_contract(const ImageRGBA& image, std::string* where = nullptr);

// Rounds a float to the nearest half (ties to even; 65504 stays, larger gives infinity):
// inputs are made exact in half so that both formats see the same scene.
float round_to_half(float value);

// One case's scene for one plugin, its tiles and masks written as float EXR into `dir`.
struct HardCaseScene {
    SceneDesc scene;
    double time = 2.5;
    double peak_input = 0;  // the largest |channel| of any tile pixel
    std::string note;       // what a reader must know about this case for this plugin
};
Result<HardCaseScene> make_hard_case_scene(const std::string& plugin, const std::string& hard_case,
                                           const std::filesystem::path& dir);

}  // namespace acetate::bench
