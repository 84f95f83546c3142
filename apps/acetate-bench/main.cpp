// `acetate-bench`: each plugin's presets and target formats as speed against error
// (docs/performance.md, "Speed against error"). Progress goes to stderr, the tables to stdout,
// the report to --html DIR and --json FILE.

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "../flag_values.hpp"
#include "bench_outputs.hpp"
#include "bench_runner.hpp"
#include "core/atomic_file.hpp"
#include "hard_cases.hpp"
#include "report.hpp"
#include "scaling.hpp"

namespace {

namespace fs = std::filesystem;
using namespace acetate;
using namespace acetate::bench;

int fail(const std::string& message) {
    std::fprintf(stderr, "acetate-bench: %s\n", message.c_str());
    return 1;
}

std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> out;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        if (comma > start) out.push_back(text.substr(start, comma - start));
        start = comma + 1;
    }
    return out;
}

std::string psnr_text(double psnr) {
    return std::isinf(psnr) ? "inf" : fmt::format("{:.1f}", psnr);
}

void print_tables(const BenchResults& results) {
    std::printf("device: %s, %s, load %s, median of %u frames\n", results.device.c_str(),
                results.date.c_str(), results.load.c_str(), results.frames);
    std::string current;
    for (const ConfigResult& c : results.configs) {
        const std::string group = c.scene + "  " + c.plugin;
        if (group != current) {
            current = group;
            std::printf("\n%s (floor %u; error against %s)\n", group.c_str(), c.floor,
                        c.reference ? (c.preset + " rgba32f").c_str() : "the reference");
            std::printf("%-8s %-8s %9s %17s %9s %9s %11s %10s %10s %7s %6s %6s\n", "preset",
                        "format", "frame ms", "min-max", "first ms", "effect ms", "pixels",
                        "max round", "mean abs", "PSNR", "warn%", "fail%");
        }
        std::printf(
            "%-8s %-8s %9.2f %8.2f-%-8.2f %9.2f %9.2f %11llu %10.4g %10.3g %7s %6.2f %6.2f%s\n",
            c.preset.c_str(), c.format.c_str(), c.median_ms, c.min_ms, c.max_ms, c.first_frame_ms,
            c.effect_gpu_ms, static_cast<unsigned long long>(c.pixels_shaded),
            c.error.max_roundings, c.error.mean_abs, psnr_text(c.error.psnr_db).c_str(),
            100 * c.error.warn_share, 100 * c.error.fail_share,
            c.error.finite ? "" : "  NOT FINITE");
    }
    for (const FrameLimits& l : results.limits) {
        std::printf("\n%s against its limits (floor %u, rgba16f, its own presets)\n",
                    l.scene.c_str(), l.floor);
        std::printf("  pixels shaded %llu, necessary %llu: %.3fx the minimum\n",
                    static_cast<unsigned long long>(l.pixels_shaded),
                    static_cast<unsigned long long>(l.necessary_pixels),
                    double(l.pixels_shaded) / double(std::max<uint64_t>(l.necessary_pixels, 1)));
        std::printf("  first frame after load %.2f ms, steady %.2f ms: %.2fx\n", l.first_frame_ms,
                    l.steady_ms, l.first_frame_ms / l.steady_ms);
        if (l.switch_floor >= 0)
            std::printf("  switch to floor %lld: first frame %.2f ms, steady %.2f ms: %.2fx\n",
                        static_cast<long long>(l.switch_floor), l.switch_ms, l.switch_steady_ms,
                        l.switch_ms / l.switch_steady_ms);
    }
    for (const PeerComparison& p : results.peers) {
        std::printf("\n%s flattened without effects: %s\n", p.scene.c_str(), p.tool.c_str());
        std::printf("  %s: %.1f ms per run, %.1f ms in its --over operations\n", p.tool.c_str(),
                    p.tool_ms, p.tool_over_ms);
        std::printf("  acetate: %.2f ms per frame, %.1f ms load + first frame + EXR written\n",
                    p.acetate_frame_ms, p.acetate_run_ms);
        std::printf("  ratio (tool / acetate): %.2fx per flattening, %.2fx per run\n",
                    p.tool_over_ms / p.acetate_frame_ms, p.tool_ms / p.acetate_run_ms);
        std::printf("  difference: max %.3g (%.3g half roundings), mean %.3g, PSNR %s dB\n",
                    p.difference.max_abs, p.difference.max_roundings, p.difference.mean_abs,
                    psnr_text(p.difference.psnr_db).c_str());
    }
}

// --hard-cases: the stability table, printed as markdown (docs/performance.md holds it).
int run_hard_case_table(const std::vector<std::string>& plugins,
                        const std::vector<std::string>& plugin_paths) {
    std::vector<fs::path> paths(plugin_paths.begin(), plugin_paths.end());
    auto device = open_device(paths);
    if (!device) return fail(device.error().message);
    std::fprintf(stderr, "acetate-bench: hard cases on %s\n",
                 device->context->device_name().c_str());
    auto table = run_hard_cases(*device->renderer, plugins, [](const std::string& line) {
        std::fprintf(stderr, "%s\n", line.c_str());
    });
    if (!table) return fail(table.error().message);
    if (auto clean = device->check_validation(); !clean) return fail(clean.error().message);
    std::printf("%s", hard_cases_markdown(table.value()).c_str());
    const bool all_pass =
        std::all_of(table->begin(), table->end(), [](const HardCaseResult& r) { return r.pass; });
    return all_pass ? 0 : 2;  // 2: a cell failed (the table says which)
}

// --scaling: the scaling series and the cost model, printed as markdown.
int run_scaling_study(uint32_t frames, const std::vector<std::string>& plugin_paths) {
    std::vector<fs::path> paths(plugin_paths.begin(), plugin_paths.end());
    auto device = open_device(paths);
    if (!device) return fail(device.error().message);
    std::fprintf(stderr, "acetate-bench: scaling on %s\n", device->context->device_name().c_str());
    ScalingOptions options;
    options.frames = frames;
    auto study = run_scaling(*device->renderer, options, [](const std::string& line) {
        std::fprintf(stderr, "%s\n", line.c_str());
    });
    if (!study) return fail(study.error().message);
    if (auto clean = device->check_validation(); !clean) return fail(clean.error().message);
    std::printf("%s", scaling_markdown(study.value()).c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "acetate-bench: frame time, GPU time per pass, pixels shaded and error against the "
        "reference (ultra, or a plugin's last preset; rgba32f) for every plugin x preset x "
        "format of each scene"};
    BenchOptions options;
    std::vector<std::string> scenes;
    std::string plugins, formats = "rgba16f,rgba32f";
    std::optional<std::string> presets;
    std::optional<std::string> html, json;
    std::optional<uint32_t> floor;
    std::vector<std::string> plugin_paths;
    bool no_peers = false, hard_cases = false, scaling = false;
    app.add_option("scenes", scenes, "scene files (acetate-scene/1 JSON)");
    app.add_flag("--hard-cases", hard_cases,
                 "instead of scenes: each plugin on alpha 2^-24, colour 65504, 16 floors, 1x1, "
                 "odd sizes and time 1e5 s, as a markdown table");
    app.add_flag("--scaling", scaling,
                 "instead of scenes: frame time against floors, effects per floor and canvas, "
                 "with a fitted cost model, as markdown");
    app.add_option("--plugins", plugins,
                   "comma-separated plugin ids (default: every plugin named)");
    app.add_option("--presets", presets,
                   "comma-separated presets (default: every preset each plugin declares)");
    app.add_option("--formats", formats, "comma-separated target formats")->capture_default_str();
    // Numbers go through the one reader (apps/flag_values.hpp): finite, in range, no wrap.
    flags::add_number(&app, "--frames", options.frames, 1, 10000,
                      "timed frames per configuration, after the first");
    flags::add_number(&app, "--time", options.time, -flags::kMaxTimeSeconds, flags::kMaxTimeSeconds,
                      "animation time of every frame (seconds)");
    flags::add_number(&app, "--floor", floor, 0, UINT32_MAX, "active floor (default: the scene's)");
    app.add_option("--html", html, "write the report (index.html, heat maps, charts) here");
    app.add_option("--json", json, "write the results as JSON here");
    // One folder per occurrence, so the option never swallows the scene files after it.
    app.add_option("--plugin-path", plugin_paths, "extra plugin folder (repeatable)")
        ->allow_extra_args(false);
    flags::add_number(&app, "--warn", options.thresholds.warn, 0.0,
                      std::numeric_limits<double>::max(), "warn threshold (absolute, linear)");
    flags::add_number(&app, "--fail", options.thresholds.fail, 0.0,
                      std::numeric_limits<double>::max(), "fail threshold (absolute, linear)");
    app.add_flag("--no-peers", no_peers, "skip the oiiotool flattening");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ValidationError& e) {
        // A value a flag refuses: the reader's one line, without CLI11's second.
        std::fprintf(stderr, "acetate-bench: %s\n", e.what());
        return 2;
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    if (hard_cases) return run_hard_case_table(split_list(plugins), plugin_paths);
    if (scaling) return run_scaling_study(options.frames, plugin_paths);
    if (scenes.empty()) return fail("expected at least one scene file (or --hard-cases)");
    for (const auto& s : scenes) options.scenes.emplace_back(s);
    options.plugins = split_list(plugins);
    if (presets) options.presets = split_list(*presets);
    options.formats = split_list(formats);
    if (presets && options.presets.empty()) return fail("--presets: expected at least one preset");
    if (options.formats.empty()) return fail("--formats: expected at least one format");
    options.floor = floor;
    for (const auto& p : plugin_paths) options.plugin_paths.emplace_back(p);
    options.peers = !no_peers;
    // Outputs never replace inputs: checked before anything is created or measured.
    if (auto spared =
            check_bench_outputs(options, json ? std::optional<fs::path>(*json) : std::nullopt,
                                html ? std::optional<fs::path>(*html) : std::nullopt);
        !spared)
        return fail(spared.error().message);
    if (html) {
        std::error_code ec;
        fs::create_directories(*html, ec);
        if (ec) return fail(fmt::format("--html {}: {}", *html, ec.message()));
        options.heat_map_dir = fs::path(*html);
    }

    std::fprintf(stderr,
                 "acetate-bench: plugins are loaded without the registry's policy (the bench "
                 "measures; it ships no frame)\n");
    auto results = run_bench(
        options, [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
    if (!results) return fail(results.error().message);
    print_tables(results.value());
    if (json)
        if (auto written = write_json(*json, results.value()); !written)
            return fail(written.error().message);
    if (html) {
        if (auto written = write_html(*html, results.value()); !written)
            return fail(written.error().message);
        // Each chart alone too, for documents that show one (docs/performance.md).
        std::set<std::pair<std::string, std::string>> charts;
        for (const ConfigResult& c : results->configs) charts.insert({c.scene, c.plugin});
        for (const auto& [scene, plugin] : charts) {
            const fs::path file = fs::path(*html) / chart_name(scene, plugin);
            if (auto written =
                    write_file_atomically(file, speed_error_svg(results.value(), scene, plugin));
                !written)
                return fail(written.error().message);
        }
        std::printf("\nreport: %s\n", (fs::path(*html) / "index.html").string().c_str());
    }
    return 0;
}
