#pragma once
// acetate-bench's reports: BenchResults as JSON (every field, for scripts and for comparing
// runs) and as one self-contained HTML page (speed against error per plugin, for people).
// Everything named in them (scenes, plugin ids, commands) comes from files, so the HTML escapes
// all of it.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "bench_results.hpp"
#include "core/result.hpp"

namespace acetate::bench {

// Every field of BenchResults, named as in bench_results.hpp. JSON has no infinity or NaN: an
// infinite number (an identical image's PSNR, a broken image's errors) is the string "inf" or
// "-inf", and a NaN is null.
nlohmann::json to_json(const BenchResults& results);

// to_json() written to `file` atomically (core/atomic_file.hpp), indented, creating its folder.
// Errors are one line naming the file.
Result<void> write_json(const std::filesystem::path& file, const BenchResults& results);

// The speed-against-error chart of one plugin on one scene, as a standalone SVG document
// (inline styles, no external resources): x the median frame milliseconds with min-max
// whiskers, y the mean absolute error on a log10 axis with a floor row for 0 (the reference),
// the Pareto front highlighted and the "off" preset as a dashed vertical line. A pair with no
// results gives a small chart saying so.
std::string speed_error_svg(const BenchResults& results, const std::string& scene,
                            const std::string& plugin);

// The whole report page as text (what write_html writes).
std::string render_html(const BenchResults& results);

// Writes `directory/index.html` (creating the folder) atomically: one self-contained page
// whose only external resources are the heat-map PNGs named in ConfigResult::heat_map, which
// the runner writes into the same folder.
Result<void> write_html(const std::filesystem::path& directory, const BenchResults& results);

}  // namespace acetate::bench
