// acetate-bench --hard-cases (hard_cases.hpp): render, check, tabulate.

#include "hard_cases.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "config_measure.hpp"
#include "image_compare.hpp"

namespace acetate::bench {
namespace {

namespace fs = std::filesystem;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Each plugin's tolerance, in hard_case_roundings() units, and the level those are taken at.
struct Tolerance {
    bool blur = false;  // level = the case's peak input (else 0: the reference value alone)
    double roundings = 0;
    const char* why = "";
    double own_level = 0;  // a level the effect adds of its own (fire's flames), at least
};

const Tolerance& tolerance_of(const std::string& plugin) {
    // One stored rounding is under 1 spacing, not 0.5: Vulkan lets a float attachment round
    // toward zero, and lavapipe does (every rgba16f value it stores is at or below rgba32f's).
    static const std::map<std::string, Tolerance> table = {
        {"acetate.lighting",
         {false, 1.0,
          "one pass, pointwise, on exact inputs: only its result is stored, one rounding (< 1 "
          "toward zero)"}},
        {"acetate.bloom",
         {true, 4.72,
          "1 for the result, plus 0.6 (intensity) / 5 (levels) x 31 for up1: down level k "
          "carries k roundings (15 over 5 levels) and each of 4 up levels one at <= 5x the "
          "level (4 each)"}},
        {"acetate.water",
         {true, 2.2,
          "1 for its one stored result, plus 1.2 for its wave texture, stored in the floor's "
          "format: the caustic factor moves by <= 0.6 x 4 x 2^-11 of the bed; refraction mixes "
          "bed texels, hence the peak level"}},
        {"acetate.specular",
         {false, 1.0,
          "one pass, pointwise, on exact inputs and masks: only its result is stored, one "
          "rounding (< 1 toward zero)"}},
        {"acetate.fire",
         {true, 9.0,
          "1 for the glow pass, plus 1 per particle blended OVER the pixel (8: one emitter's "
          "5 flames, 2 embers, 1 smoke at the defaults), at the level of the flames' emission "
          "(3, the default intensity) or the floor's peak",
          3.0}},
    };
    static const Tolerance unknown{false, 1.0, "one stored rounding"};
    auto it = table.find(plugin);
    return it == table.end() ? unknown : it->second;
}

std::string cell_text(const HardCaseResult& r) {
    if (!r.finite) return "✗ NaN/inf";
    if (!r.contract) return "✗ contract";
    return fmt::format("{} {:.2f}", r.pass ? "✓" : "✗", r.max_roundings);
}

}  // namespace

double hard_case_roundings(const ImageRGBA& test, const ImageRGBA& reference, double level) {
    double worst = 0;
    const size_t n = std::min(test.pixels.size(), reference.pixels.size());
    for (size_t i = 0; i < n; ++i) {
        const double t = test.pixels[i], r = reference.pixels[i];
        if (!std::isfinite(t)) return kInfinity;
        const double unit = half_spacing(std::max(std::fabs(r), level));
        worst = std::max(worst, std::fabs(t - r) / unit);
    }
    return worst;
}

bool keeps_contract(const ImageRGBA& image, std::string* where) {
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const float* p = image.at(x, y);
            const bool bad = p[3] < 0 || (p[3] == 0 && (p[0] != 0 || p[1] != 0 || p[2] != 0));
            if (!bad) continue;
            if (where) *where = fmt::format("({}, {}) {} {} {} {}", x, y, p[0], p[1], p[2], p[3]);
            return false;
        }
    return true;
}

Result<std::vector<HardCaseResult>> run_hard_cases(Renderer& renderer,
                                                   const std::vector<std::string>& plugins,
                                                   const ProgressFn& progress) {
    const std::vector<std::string>& ids = plugins.empty() ? shipped_plugins() : plugins;
    for (const std::string& id : ids)
        if (std::find(shipped_plugins().begin(), shipped_plugins().end(), id) ==
            shipped_plugins().end())
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("--hard-cases: {} is not a shipped plugin (they are: "
                                          "acetate.lighting, acetate.bloom, acetate.water, "
                                          "acetate.specular, acetate.fire)",
                                          id));
    const fs::path root =
        fs::temp_directory_path() / fmt::format("acetate-bench-hard-cases-{}", ::getpid());
    struct Cleanup {
        fs::path dir;
        ~Cleanup() {
            std::error_code ec;
            fs::remove_all(dir, ec);
        }
    } cleanup{root};

    std::vector<HardCaseResult> results;
    const size_t total = ids.size() * hard_case_names().size();
    for (const std::string& plugin : ids) {
        const Tolerance& tolerance = tolerance_of(plugin);
        for (const std::string& hard_case : hard_case_names()) {
            if (progress)
                progress(
                    fmt::format("[{}/{}] {} {}", results.size() + 1, total, plugin, hard_case));
            const fs::path dir = root / fmt::format("case{}", results.size());
            auto made = make_hard_case_scene(plugin, hard_case, dir);
            if (!made) return made.error();
            const HardCaseScene& hc = made.value();
            const uint32_t floor = hc.scene.active_floor;
            auto half = measure_config(renderer, hc.scene, VK_FORMAT_R16G16B16A16_SFLOAT, floor, 1,
                                       hc.time);
            if (!half) return half.error();
            auto full = measure_config(renderer, hc.scene, VK_FORMAT_R32G32B32A32_SFLOAT, floor, 1,
                                       hc.time);
            if (!full) return full.error();
            std::error_code ec;
            fs::remove_all(dir, ec);

            HardCaseResult r;
            r.plugin = plugin;
            r.hard_case = hard_case;
            r.tolerance = tolerance.roundings;
            r.why = tolerance.why;
            r.note = hc.note;
            r.level = tolerance.blur ? std::max(hc.peak_input, tolerance.own_level) : 0.0;
            const ImageRGBA& test = half->image;
            const ImageRGBA& reference = full->image;
            r.finite = std::all_of(test.pixels.begin(), test.pixels.end(),
                                   [](float v) { return std::isfinite(v); });
            std::string where;
            r.contract = keeps_contract(test, &where);
            if (!r.contract) r.note += (r.note.empty() ? "" : "; ") + ("rgba16f " + where);
            if (!keeps_contract(reference, &where))
                r.note += (r.note.empty() ? "" : "; ") + ("rgba32f breaks it too: " + where);
            auto stats = compare_images(test, reference, ErrorThresholds{});
            if (!stats)
                return make_error(stats.error().code, fmt::format("{} {}: {}", plugin, hard_case,
                                                                  stats.error().message));
            r.roundings_at_reference = stats->max_roundings;
            r.max_roundings = hard_case_roundings(test, reference, r.level);
            r.pass = r.finite && r.contract && r.max_roundings <= r.tolerance;
            double peak = 0;
            for (float v : reference.pixels) peak = std::max(peak, double(std::fabs(v)));
            if (peak > 65504.0)
                r.note += (r.note.empty() ? "" : "; ") +
                          fmt::format(
                              "rgba32f reaches {:.4g}, past the largest half (65504): "
                              "rgba16f holds {} there (this device rounds toward zero; "
                              "one rounding to nearest stores inf)",
                              peak, r.finite ? "65504" : "inf");
            results.push_back(std::move(r));
        }
    }
    return results;
}

std::string hard_cases_markdown(const std::vector<HardCaseResult>& results) {
    std::vector<std::string> plugins, cases;
    for (const HardCaseResult& r : results) {
        if (std::find(plugins.begin(), plugins.end(), r.plugin) == plugins.end())
            plugins.push_back(r.plugin);
        if (std::find(cases.begin(), cases.end(), r.hard_case) == cases.end())
            cases.push_back(r.hard_case);
    }
    std::string out = "| plugin |";
    std::string rule = "|---|";
    for (const std::string& c : cases) out += " " + c + " |", rule += "---|";
    out += "\n" + rule + "\n";
    std::vector<std::string> notes;
    for (const std::string& plugin : plugins) {
        out += "| " + plugin + " |";
        for (const std::string& c : cases) {
            auto it = std::find_if(results.begin(), results.end(), [&](const HardCaseResult& r) {
                return r.plugin == plugin && r.hard_case == c;
            });
            if (it == results.end()) {
                out += " — |";
                continue;
            }
            std::string cell = cell_text(*it);
            if (!it->note.empty()) {
                notes.push_back(fmt::format("{} {}: {}", plugin, c, it->note));
                cell += fmt::format(" [{}]", notes.size());
            }
            out += " " + cell + " |";
        }
        out += "\n";
    }
    out +=
        "\nEach cell: ✓ or ✗, then the largest error of the rgba16f render against the "
        "rgba32f render of the same case, in half-float roundings: |rgba16f - rgba32f| / "
        "half_spacing(max(|rgba32f|, level)) over every channel of every pixel, where level "
        "is 0 for pointwise effects and the case's peak input level for effects that sum "
        "stored values (a blur). Inputs are exact in half, tiles are drawn 1:1, so the two "
        "renders differ only in what the frame stores. ✗ NaN/inf: the rgba16f output is not "
        "finite; ✗ contract: it has rgb != 0 where alpha is 0, or a negative alpha.\n\n";
    for (const std::string& plugin : plugins) {
        auto it = std::find_if(results.begin(), results.end(),
                               [&](const HardCaseResult& r) { return r.plugin == plugin; });
        out +=
            fmt::format("- {}: tolerance {:.2f} roundings{}: {}\n", plugin, it->tolerance,
                        it->level > 0 ? " (level: the case's peak input)" : " (level 0)", it->why);
    }
    if (!notes.empty()) {
        out += "\n";
        for (size_t i = 0; i < notes.size(); ++i) out += fmt::format("[{}] {}\n", i + 1, notes[i]);
    }
    return out;
}

}  // namespace acetate::bench
