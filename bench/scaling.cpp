// acetate-bench --scaling (scaling.hpp): the series, the measurements and the cost model.

#include "scaling.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <tuple>

#include "render/compositor.hpp"
#include "render/renderer.hpp"
#include "scene/scene.hpp"

namespace acetate::bench {
namespace {

namespace fs = std::filesystem;

constexpr double kTime = 2.5;  // seconds: what every frame shows
// Timed frames per round: `frames`, but no more than fit in this many milliseconds (judged by
// the warm-up frame), and at least 3: the heavy points (a second or more per frame on
// lavapipe) would otherwise take most of the run.
constexpr double kRoundBudgetMs = 4000;
constexpr uint32_t kMinFrames = 3;
// Rounds over every configuration (the full study): the machine is shared, and another
// process's burst of work lands on some points; the round with the lower median is kept.
constexpr uint32_t kRounds = 2;
constexpr double kSignificance = 2.0;  // |t| under which passes is dropped
constexpr double kCollinear = 1e-9;    // 1 - corr(pixels, passes)^2 under this

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string loadavg() {
    std::ifstream in("/proc/loadavg");
    std::string line;
    std::getline(in, line);
    return line;
}

struct Config {
    uint32_t width = 0, height = 0, floors = 0, effects = 0;
    auto key() const { return std::tie(width, height, floors, effects); }
    bool operator<(const Config& o) const { return key() < o.key(); }
};

struct Measured {
    double median_ms = 0, min_ms = 0, max_ms = 0, load_ms = 0;
    double other_round_ms = 0;  // the median of the round not kept (0 with one round)
    uint64_t pixels_shaded = 0;
    uint32_t passes = 0, frames = 0;
};

std::string describe(const Config& c) {
    return fmt::format("{}×{}, {} floor{}, {} effect{} per floor", c.width, c.height, c.floors,
                       c.floors == 1 ? "" : "s", c.effects, c.effects == 1 ? "" : "s");
}

Result<Measured> measure(Renderer& renderer, const fs::path& scene_file, uint32_t frames) {
    auto scene = parse_scene_file(scene_file);
    if (!scene) return scene.error();
    CompositorOptions options;
    options.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    auto compositor = Compositor::load(renderer, scene.value(), options);
    if (!compositor) return compositor.error();
    Compositor& c = *compositor.value();
    const uint32_t floor = scene->active_floor;
    Measured m;
    m.load_ms = c.load_stats().milliseconds;
    auto warm = c.render(floor, kTime);  // the first frame after load: not timed
    if (!warm) return warm.error();
    frames = std::clamp(uint32_t(std::ceil(kRoundBudgetMs / std::max(warm->milliseconds, 1e-3))),
                        std::min(kMinFrames, frames), frames);
    std::vector<double> ms;
    for (uint32_t i = 0; i < frames; ++i) {
        auto stats = c.render(floor, kTime);
        if (!stats) return stats.error();
        ms.push_back(stats->milliseconds);
        m.pixels_shaded = stats->pixels_shaded;
        m.passes = stats->passes;
    }
    m.frames = frames;
    m.median_ms = median(ms);
    m.min_ms = *std::min_element(ms.begin(), ms.end());
    m.max_ms = *std::max_element(ms.begin(), ms.end());
    return m;
}

// 1,234,567
std::string grouped(uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

// "water" for effects_per_floor 3: the effect that step adds.
std::string added_effect(uint32_t effects) {
    const std::string& id = scaling_effect_plugins()[effects - 1];
    std::string name = id.substr(id.find('.') + 1);
    if (effects == 5) name += " again";
    return name;
}

std::string effect_label(uint32_t effects) {
    if (effects == 0) return "0 (none)";
    return fmt::format("{} (+ {})", effects, added_effect(effects));
}

std::string point_label(const ScalingPoint& p) {
    if (p.series == "floors") return fmt::format("{}", p.floors);
    if (p.series == "effects") return effect_label(p.effects_per_floor);
    return fmt::format("{}×{}", p.width, p.height);
}

std::string effects_list(uint32_t effects) {
    if (effects == 0) return "none";
    std::string out;
    for (uint32_t e = 0; e < effects; ++e) out += (e ? ", " : "") + scaling_effect_plugins()[e];
    return out;
}

std::string signed_percent(double share) {
    return fmt::format("{:+.1f}%", 100.0 * share);
}

}  // namespace

// ---- the cost model -----------------------------------------------------------------------

CostModel fit_cost_model(const std::vector<ScalingPoint>& points) {
    CostModel model;
    const size_t n = points.size();
    model.fitted_points = uint32_t(n);
    if (n == 0) return model;
    // Centred sums, pixels in megapixels: a ms per megapixel is a ns per pixel.
    double m1 = 0, m2 = 0, my = 0;
    for (const ScalingPoint& p : points) {
        m1 += double(p.pixels_shaded) * 1e-6;
        m2 += double(p.passes);
        my += p.median_ms;
    }
    m1 /= double(n), m2 /= double(n), my /= double(n);
    double s11 = 0, s12 = 0, s22 = 0, s1y = 0, s2y = 0, syy = 0;
    for (const ScalingPoint& p : points) {
        const double x1 = double(p.pixels_shaded) * 1e-6 - m1, x2 = double(p.passes) - m2,
                     y = p.median_ms - my;
        s11 += x1 * x1, s12 += x1 * x2, s22 += x2 * x2;
        s1y += x1 * y, s2y += x2 * y, syy += y * y;
    }
    double a = 0, b = 0;
    bool three = false;
    const double det = s11 * s22 - s12 * s12;
    if (n >= 4 && s11 > 0 && s22 > 0 && det > kCollinear * s11 * s22) {
        // The 3x3 normal equations, with the intercept eliminated by centring.
        a = (s22 * s1y - s12 * s2y) / det;
        b = (s11 * s2y - s12 * s1y) / det;
        double ssr = 0;
        for (const ScalingPoint& p : points) {
            const double r = p.median_ms - (my + a * (double(p.pixels_shaded) * 1e-6 - m1) +
                                            b * (double(p.passes) - m2));
            ssr += r * r;
        }
        // var(b) = s^2 (X'X)^-1 [b][b], s^2 = SSR / (n - 3).
        const double var_b = ssr / double(n - 3) * s11 / det;
        model.passes_t = var_b > 0 ? b / std::sqrt(var_b)
                                   : (b == 0 ? 0 : std::numeric_limits<double>::infinity());
        three = std::fabs(model.passes_t) >= kSignificance;
    }
    if (!three) {
        model.passes_dropped = true;
        b = 0;
        a = s11 > 0 ? s1y / s11 : 0;
    }
    model.ns_per_pixel = a;
    model.ms_per_pass = b;
    model.fixed_ms = my - a * m1 - b * m2;
    double ssr = 0;
    for (const ScalingPoint& p : points) {
        const double r = p.median_ms - predict_ms(model, p.pixels_shaded, p.passes);
        ssr += r * r;
    }
    model.r_squared = syy > 0 ? 1.0 - ssr / syy : 1.0;
    model.formula = fmt::format("frame_ms ≈ {:.3g} ms + {:.3g} ns/pixel × pixels_shaded",
                                model.fixed_ms, model.ns_per_pixel);
    if (!model.passes_dropped)
        model.formula += fmt::format(" + {:.3g} ms/pass × passes", model.ms_per_pass);
    return model;
}

double predict_ms(const CostModel& model, uint64_t pixels_shaded, uint32_t passes) {
    return model.fixed_ms + model.ns_per_pixel * double(pixels_shaded) * 1e-6 +
           model.ms_per_pass * double(passes);
}

void apply_cost_model(const CostModel& model, std::vector<ScalingPoint>& points) {
    for (ScalingPoint& p : points) {
        p.model_ms = predict_ms(model, p.pixels_shaded, p.passes);
        p.residual = p.model_ms > 0 ? (p.median_ms - p.model_ms) / p.model_ms : 0.0;
    }
}

// ---- the run ------------------------------------------------------------------------------

Result<ScalingResults> run_scaling(Renderer& renderer, const ScalingOptions& options,
                                   const ProgressFn& progress) {
    struct SeriesPoint {
        std::string series;
        Config config;
    };
    std::vector<SeriesPoint> plan;
    const uint32_t base_w = options.quick ? 64 : 1920, base_h = options.quick ? 48 : 1080;
    const std::vector<uint32_t> floors =
        options.quick ? std::vector<uint32_t>{1, 2, 4} : std::vector<uint32_t>{1, 2, 4, 8, 16};
    const std::vector<std::pair<uint32_t, uint32_t>> canvases =
        options.quick ? std::vector<std::pair<uint32_t, uint32_t>>{{64, 48}, {96, 72}, {128, 96}}
                      : std::vector<std::pair<uint32_t, uint32_t>>{
                            {1280, 720}, {1920, 1080}, {2560, 1440}, {3840, 2160}};
    for (uint32_t f : floors) plan.push_back({"floors", {base_w, base_h, f, 1}});
    for (uint32_t e = 0; e <= 5; ++e) plan.push_back({"effects", {base_w, base_h, 4, e}});
    for (auto [w, h] : canvases) plan.push_back({"canvas", {w, h, 4, 1}});

    std::vector<Config> distinct;
    for (const SeriesPoint& s : plan)
        if (std::find_if(distinct.begin(), distinct.end(), [&](const Config& c) {
                return !(c < s.config) && !(s.config < c);
            }) == distinct.end())
            distinct.push_back(s.config);

    const fs::path dir =
        fs::temp_directory_path() / fmt::format("acetate-bench-scaling-{}", ::getpid());
    struct Cleanup {
        fs::path dir;
        ~Cleanup() {
            std::error_code ec;
            fs::remove_all(dir, ec);
        }
    } cleanup{dir};
    if (auto written = write_scaling_assets(dir, options.quick ? 64 : 512); !written)
        return make_error(written.error().code,
                          "--scaling: writing the tiles: " + written.error().message);

    ScalingResults results;
    results.load_before = loadavg();
    std::vector<fs::path> files;
    for (size_t i = 0; i < distinct.size(); ++i) {
        const Config& c = distinct[i];
        auto file = write_scaling_scene(dir, fmt::format("scene{}.json", i), c.width, c.height,
                                        c.floors, c.effects);
        if (!file) return file.error();
        files.push_back(file.value());
    }
    const uint32_t rounds = options.quick ? 1 : kRounds;
    std::map<Config, Measured> measured;
    for (uint32_t round = 0; round < rounds; ++round)
        for (size_t i = 0; i < distinct.size(); ++i) {
            const Config& c = distinct[i];
            if (progress)
                progress(fmt::format(
                    "[{}/{}] {}{}", round * distinct.size() + i + 1, rounds * distinct.size(),
                    rounds > 1 ? fmt::format("round {}: ", round + 1) : "", describe(c)));
            auto m = measure(renderer, files[i], std::max(1u, options.frames));
            if (!m)
                return make_error(m.error().code,
                                  fmt::format("--scaling: {}: {}", describe(c), m.error().message));
            auto it = measured.find(c);
            if (it == measured.end()) {
                measured[c] = m.value();
            } else if (m->median_ms < it->second.median_ms) {
                const double other = it->second.median_ms;
                it->second = m.value();
                it->second.other_round_ms = other;
            } else {
                it->second.other_round_ms = m->median_ms;
            }
        }
    results.load_after = loadavg();

    for (const SeriesPoint& s : plan) {
        const Measured& m = measured.at(s.config);
        ScalingPoint p;
        p.series = s.series;
        p.width = s.config.width;
        p.height = s.config.height;
        p.floors = s.config.floors;
        p.effects_per_floor = s.config.effects;
        p.median_ms = m.median_ms;
        p.min_ms = m.min_ms;
        p.max_ms = m.max_ms;
        p.pixels_shaded = m.pixels_shaded;
        p.passes = m.passes;
        p.frames = m.frames;
        p.load_ms = m.load_ms;
        p.other_round_ms = m.other_round_ms;
        results.points.push_back(p);
    }
    // Fit on each configuration once (a point in two series would otherwise weigh double).
    std::vector<ScalingPoint> fit_on;
    for (const Config& c : distinct)
        for (const ScalingPoint& p : results.points)
            if (p.width == c.width && p.height == c.height && p.floors == c.floors &&
                p.effects_per_floor == c.effects) {
                fit_on.push_back(p);
                break;
            }
    results.model = fit_cost_model(fit_on);
    apply_cost_model(results.model, results.points);
    return results;
}

// ---- the markdown -------------------------------------------------------------------------

std::string scaling_markdown(const ScalingResults& results) {
    std::string md = "## Scaling: frame time against floors, effects per floor and canvas\n\n";
    if (results.points.empty()) return md + "No points were measured.\n";

    uint32_t most_frames = 0;
    const ScalingPoint* noisiest = nullptr;  // the largest gap between the two rounds
    auto gap = [](const ScalingPoint& p) {
        return p.other_round_ms > 0 ? p.other_round_ms / p.median_ms - 1.0 : 0.0;
    };
    for (const ScalingPoint& p : results.points) {
        most_frames = std::max(most_frames, p.frames);
        if (p.other_round_ms > 0 && (!noisiest || gap(p) > gap(*noisiest))) noisiest = &p;
    }
    md += fmt::format(
        "Generated scenes: each floor three partly overlapping tiles with feathered alpha edges "
        "(about {:.0f}% of the canvas), four lights and a sun; the top floor active, so every "
        "floor is composited; rgba16f targets, the plugins' defaults, t = 2.5 s. Effects are "
        "added in the order {}. Frame time is wall clock (record + submit + wait): the median "
        "of the timed frames after one warm-up frame ({} at most, fewer where they would take "
        "over 4 s, 3 at least; the `frames` column), min–max in brackets. ",
        100.0 * scaling_floor_coverage(1920, 1080, 0), effects_list(5), most_frames);
    if (noisiest)
        md += fmt::format(
            "Each configuration was measured in two rounds, each with a fresh load, and the "
            "round with the lower median is shown (the machine is shared; contention only adds "
            "time); the other round's median was up to {:.0f}% higher ({}×{}, {} floors, {} "
            "effects). ",
            100.0 * gap(*noisiest), noisiest->width, noisiest->height, noisiest->floors,
            noisiest->effects_per_floor);
    md += fmt::format("Load average (/proc/loadavg) {} before, {} after.\n\n",
                      results.load_before.empty() ? "?" : results.load_before.substr(0, 14),
                      results.load_after.empty() ? "?" : results.load_after.substr(0, 14));

    struct Series {
        const char* name;
        const char* column;
    };
    for (const Series& s : {Series{"floors", "floors"}, Series{"effects", "effects per floor"},
                            Series{"canvas", "canvas"}}) {
        std::vector<const ScalingPoint*> rows;
        for (const ScalingPoint& p : results.points)
            if (p.series == s.name) rows.push_back(&p);
        if (rows.empty()) continue;
        const ScalingPoint& first = *rows.front();
        if (std::string(s.name) == "floors")
            md += fmt::format("### Floors ({}×{}, {} effect per floor: {})\n\n", first.width,
                              first.height, first.effects_per_floor,
                              effects_list(first.effects_per_floor));
        else if (std::string(s.name) == "effects")
            md += fmt::format("### Effects per floor ({}×{}, {} floors)\n\n", first.width,
                              first.height, first.floors);
        else
            md += fmt::format("### Canvas ({} floors, {} effect per floor: {})\n\n", first.floors,
                              first.effects_per_floor, effects_list(first.effects_per_floor));
        md += fmt::format(
            "| {} | passes | pixels shaded | median ms (min–max) | model ms | "
            "residual | frames |\n|---|---:|---:|---:|---:|---:|---:|\n",
            s.column);
        for (const ScalingPoint* p : rows)
            md += fmt::format("| {} | {} | {} | {:.1f} ({:.1f}–{:.1f}) | {:.1f} | {} | {} |\n",
                              point_label(*p), p->passes, grouped(p->pixels_shaded), p->median_ms,
                              p->min_ms, p->max_ms, p->model_ms, signed_percent(p->residual),
                              p->frames);
        md += "\n";
    }

    const CostModel& m = results.model;
    md += fmt::format(
        "**Cost model** (ordinary least squares over the {} distinct configurations; a point "
        "listed in two series counts once): {}, R² = {:.4f}.",
        m.fitted_points, m.formula, m.r_squared);
    if (m.passes_dropped) {
        if (m.passes_t != 0)
            md += fmt::format(
                " The per-pass term was dropped: its t statistic in the three-parameter fit was "
                "{:.2f} (under 2), so a pass's fixed cost cannot be told apart from the noise "
                "here.",
                m.passes_t);
        else
            md +=
                " The per-pass term was dropped: too few points, or passes that do not vary "
                "apart from pixels shaded, to fit it.";
    } else {
        md += fmt::format(" The per-pass term is significant (t = {:.1f}).", m.passes_t);
    }
    if (m.fixed_ms < 0)
        md += fmt::format(
            " The negative fixed cost has no physical meaning: the heavy effects' pixels pull the "
            "per-pixel rate above what tiles, composites and lighting cost, and the intercept "
            "makes up for it on the light points.");
    md += "\n\n";

    // What each effect adds per pixel it adds (effects series, one step to the next): the
    // reason one rate for every pixel cannot fit all the points.
    std::vector<const ScalingPoint*> effects;
    for (const ScalingPoint& p : results.points)
        if (p.series == "effects") effects.push_back(&p);
    std::map<uint32_t, double> marginal;  // effects_per_floor -> ns per added pixel shaded
    std::string steps;
    for (size_t i = 1; i < effects.size(); ++i) {
        const ScalingPoint &from = *effects[i - 1], &to = *effects[i];
        if (to.pixels_shaded <= from.pixels_shaded) continue;
        const double ns =
            (to.median_ms - from.median_ms) * 1e6 / double(to.pixels_shaded - from.pixels_shaded);
        marginal[to.effects_per_floor] = ns;
        steps += fmt::format("{}{} {:.0f}", steps.empty() ? "" : ", ",
                             added_effect(to.effects_per_floor), ns);
    }
    if (!steps.empty())
        md += fmt::format(
            "What each effect adds per pixel it adds to the frame (effects series, Δ median / Δ "
            "pixels shaded, ns/pixel): {}; the model's one rate is {:.3g}.\n\n",
            steps, m.ns_per_pixel);

    const ScalingPoint* worst = nullptr;
    for (const ScalingPoint& p : results.points)
        if (!worst || std::fabs(p.residual) > std::fabs(worst->residual)) worst = &p;
    md += fmt::format(
        "The worst point is {}×{} with {} floor{} and {} effect{} per floor ({}): {:.1f} ms "
        "measured against {:.1f} ms predicted ({})",
        worst->width, worst->height, worst->floors, worst->floors == 1 ? "" : "s",
        worst->effects_per_floor, worst->effects_per_floor == 1 ? "" : "s",
        effects_list(worst->effects_per_floor), worst->median_ms, worst->model_ms,
        signed_percent(worst->residual));
    auto it = marginal.find(worst->effects_per_floor);
    const bool on_effects = !effects.empty() && worst->width == effects.front()->width &&
                            worst->height == effects.front()->height &&
                            worst->floors == effects.front()->floors;
    if (on_effects && it != marginal.end())
        md += fmt::format(
            ": {} costs {:.0f} ns per pixel it shades, {} the {:.3g} the model gives every "
            "pixel.\n",
            scaling_effect_plugins()[worst->effects_per_floor - 1], it->second,
            it->second > m.ns_per_pixel ? "above" : "below", m.ns_per_pixel);
    else
        md += fmt::format(
            "; the model prices every shaded pixel alike, so a point whose passes do {} work "
            "per pixel than the average lies {} it.\n",
            worst->residual > 0 ? "more" : "less", worst->residual > 0 ? "above" : "below");
    return md;
}

}  // namespace acetate::bench
