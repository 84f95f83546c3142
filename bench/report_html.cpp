// index.html of an acetate-bench run and its speed-against-error charts (report.hpp): one
// self-contained page, inline CSS and SVG, no script; its only external resources are the
// heat-map PNGs next to it. Scene names, plugin ids and commands come from files, so every
// piece of text goes through escape() and every image name through url().
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <utility>

#include "core/atomic_file.hpp"
#include "image_compare.hpp"
#include "report.hpp"
#include "report_text.hpp"

namespace acetate::bench {
namespace fs = std::filesystem;
using namespace report_detail;

namespace {

constexpr std::string_view kStyle = R"css(
:root { --line: #d0d7de; --muted: #57606a; --panel: #f6f8fa; --front: #c2410c; }
* { box-sizing: border-box; }
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: #1f2328;
       max-width: 1280px; margin: 0 auto; padding: 24px; }
h1 { font-size: 24px; margin: 0 0 2px; }
h2 { font-size: 18px; margin: 32px 0 8px; padding-bottom: 4px; border-bottom: 1px solid var(--line); }
h3 { font-size: 14px; margin: 16px 0 4px; }
a { color: #0969da; text-decoration: none; } a:hover { text-decoration: underline; }
code { font: 12.5px/1.4 ui-monospace, SFMono-Regular, Menlo, Consolas, monospace;
       overflow-wrap: anywhere; }
table { border-collapse: collapse; margin: 6px 0 12px; }
th, td { text-align: left; vertical-align: top; padding: 4px 8px; border-bottom: 1px solid var(--line); }
th { background: var(--panel); font-weight: 600; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr.front td { background: #fff4ec; } tr.front td:first-child { color: var(--front); font-weight: 700; }
.subtitle, .muted { color: var(--muted); }
dl.facts { display: grid; grid-template-columns: max-content 1fr; gap: 2px 16px; margin: 12px 0; }
dl.facts dt { color: var(--muted); } dl.facts dd { margin: 0; overflow-wrap: anywhere; }
figure { margin: 0; } figure svg { max-width: 100%; height: auto; }
.figures { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; margin: 8px 0; }
.figures img { display: block; max-width: 320px; max-height: 320px; border: 1px solid var(--line);
               image-rendering: pixelated; }
figcaption { font-size: 12px; color: var(--muted); margin-top: 2px; max-width: 320px; }
details { margin: 4px 0; } summary { cursor: pointer; }
.bar { display: inline-block; height: 10px; background: var(--front); opacity: .75; }
)css";

// Why the thresholds are what they are; a run that changed them says so instead.
std::string threshold_text(double value, double default_value, const char* reason) {
    return value == default_value ? fmt::format("{} ({})", error_text(value), reason)
                                  : fmt::format("{} (set for this run)", error_text(value));
}

// The heat maps' scale (scene/image_compare.hpp) as a gradient with the thresholds marked on it.
std::string heat_legend_svg(const ErrorThresholds& thresholds, int id) {
    const HeatMapScale& scale = heat_map_scale();
    const double x0 = 24, width = 360, lo = std::log10(scale.floor_abs),
                 hi = std::log10(scale.ceiling_abs);
    auto x = [&](double v) { return x0 + (std::log10(v) - lo) / (hi - lo) * width; };
    std::string s = fmt::format(
        R"(<svg xmlns="http://www.w3.org/2000/svg" width="520" height="58" font-size="11" )"
        R"(font-family="system-ui, sans-serif"><defs><linearGradient id="heat-ramp-{}">)",
        id);
    for (size_t i = 0; i < scale.stops.size(); ++i)
        s += fmt::format(R"(<stop offset="{:.4f}" stop-color="#{:02x}{:02x}{:02x}"/>)",
                         double(i) / double(scale.stops.size() - 1), scale.stops[i][0],
                         scale.stops[i][1], scale.stops[i][2]);
    s += fmt::format(R"(</linearGradient></defs><rect x="{}" y="8" width="{}" height="14" )"
                     R"s(fill="url(#heat-ramp-{})"/>)s",
                     x0, width, id);
    for (double v = scale.floor_abs; v <= scale.ceiling_abs * 1.001; v *= 10)
        s += fmt::format(R"(<line x1="{0:.1f}" y1="22" x2="{0:.1f}" y2="26" stroke="#57606a"/>)"
                         R"(<text x="{0:.1f}" y="37" text-anchor="middle">{1}</text>)",
                         x(v), v >= 1 ? "1" : fmt::format("1e{}", int(std::lround(std::log10(v)))));
    for (auto [value, name] :
         {std::pair(thresholds.warn, "warn"), std::pair(thresholds.fail, "fail")})
        if (value >= scale.floor_abs && value <= scale.ceiling_abs)
            s += fmt::format(
                R"(<line x1="{0:.1f}" y1="4" x2="{0:.1f}" y2="22" stroke="#fff" stroke-width="1.5"/>)"
                R"(<text x="{0:.1f}" y="51" text-anchor="middle">{1}</text>)",
                x(value), name);
    const auto& c = scale.non_finite;
    return s +
           fmt::format(R"(<rect x="{}" y="8" width="14" height="14" fill="#{:02x}{:02x}{:02x}"/>)"
                       R"(<text x="{}" y="19">not finite</text></svg>)",
                       x0 + width + 24, c[0], c[1], c[2], x0 + width + 42);
}

class Page {
  public:
    explicit Page(const BenchResults& results) : results_(results), groups_(groups_of(results)) {}

    std::string render() {
        put("<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<title>acetate-bench: {}</title>\n<style>{}</style>\n</head>\n<body>\n",
            escape(results_.device), kStyle);
        header();
        for (size_t g = 0; g < groups_.size(); ++g) group(g);
        peers();
        limits();
        put("</body>\n</html>\n");
        return std::move(out_);
    }

  private:
    template <class... Args>
    void put(fmt::format_string<Args...> format, Args&&... args) {
        out_ += fmt::format(format, std::forward<Args>(args)...);
    }

    void header() {
        const ErrorThresholds defaults;
        const ErrorThresholds& t = results_.thresholds;
        put("<h1>acetate-bench: speed against error</h1>\n<p class=\"subtitle\">Each plugin at "
            "each preset and target format: frame time against the error from its reference "
            "(the plugin at <code>ultra</code> with rgba32f targets), over premultiplied linear "
            "RGBA.</p>\n<dl class=\"facts\">\n<dt>Device</dt><dd>{}</dd>\n<dt>Date</dt><dd>{}</dd>"
            "\n<dt>Load</dt><dd>{} <span class=\"muted\">(/proc/loadavg at the start: the machine "
            "is shared)</span></dd>\n<dt>Frames</dt><dd>{} <span class=\"muted\">(timed after the "
            "first)</span></dd>\n<dt>Warn above</dt><dd>{}</dd>\n<dt>Fail above</dt><dd>{}</dd>\n"
            "</dl>\n",
            escape(results_.device), escape(results_.date), escape(results_.load), results_.frames,
            threshold_text(t.warn, defaults.warn,
                           "one half-float rounding at 1.0, 2^-10: below it rgba16f cannot tell "
                           "the images apart"),
            threshold_text(t.fail, defaults.fail,
                           "four 8-bit steps at full scale, 4/255: a difference a person can see "
                           "on a display"));
        if (groups_.empty() && results_.peers.empty()) {
            put("<p class=\"muted\">This run measured nothing.</p>\n");
            return;
        }
        put("<ul>\n");
        for (size_t g = 0; g < groups_.size(); ++g)
            put("<li><a href=\"#g{}\">{} on {}</a></li>\n", g, escape(groups_[g].plugin),
                escape(groups_[g].scene));
        if (!results_.peers.empty()) put("<li><a href=\"#peers\">Other tools</a></li>\n");
        if (!results_.limits.empty())
            put("<li><a href=\"#limits\">The frame against its limits</a></li>\n");
        put("</ul>\n");
    }

    void group(size_t index) {
        const Group& g = groups_[index];
        std::vector<uint32_t> floors;
        for (const ConfigResult* c : g.configs)
            if (std::find(floors.begin(), floors.end(), c->floor) == floors.end())
                floors.push_back(c->floor);
        put("<section id=\"g{}\">\n<h2>{} on {} <span class=\"muted\">({} "
            "{})</span></h2>\n<figure>\n{}<figcaption>Filled points are on "
            "the Pareto front: no other configuration is both as fast and as close. Points with "
            "no error (the reference) sit on the bottom row.</figcaption>\n</figure>\n",
            index, escape(g.plugin), escape(g.scene), floors.size() > 1 ? "floors" : "floor",
            fmt::join(floors, ", "), chart_svg(g));
        table(g);
        heat_maps(g, int(index));
        gpu_time(g);
        put("</section>\n");
    }

    void table(const Group& g) {
        put("<table>\n<tr><th title=\"on the Pareto front\">Front</th><th>Preset</th>"
            "<th>Format</th><th class=\"num\">Median ms (min–max)</th><th class=\"num\">First "
            "frame ms</th><th class=\"num\">Effect GPU ms</th><th class=\"num\">Load ms</th><th "
            "class=\"num\">Pixels shaded</th>"
            "<th class=\"num\">Max roundings</th><th class=\"num\">Max |error|</th>"
            "<th class=\"num\">Mean |error|</th><th class=\"num\">PSNR</th><th class=\"num\">Warn"
            "</th><th class=\"num\">Fail</th><th>Finite</th></tr>\n");
        for (size_t i = 0; i < g.configs.size(); ++i) {
            const ConfigResult& c = *g.configs[i];
            const ErrorStats& e = c.error;
            put("<tr{}><td>{}</td><td>{}{}</td><td>{}</td><td class=\"num\">{} ({}–{})</td>"
                "<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                "<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                "<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                "<td class=\"num\">{}</td><td>{}</td></tr>\n",
                g.front[i] ? " class=\"front\"" : "", g.front[i] ? "◆" : "", escape(c.preset),
                c.reference ? " <span class=\"muted\">(reference)</span>" : "", escape(c.format),
                ms_text(c.median_ms), ms_text(c.min_ms), ms_text(c.max_ms),
                ms_text(c.first_frame_ms), ms_text(c.effect_gpu_ms), ms_text(c.load_ms),
                count_text(c.pixels_shaded), error_text(e.max_roundings), error_text(e.max_abs),
                error_text(e.mean_abs), psnr_text(e.psnr_db), share_text(e.warn_share),
                share_text(e.fail_share), e.finite ? "yes" : "<strong>no</strong>");
        }
        put("</table>\n");
    }

    void heat_maps(const Group& g, int id) {
        if (std::none_of(g.configs.begin(), g.configs.end(),
                         [](const ConfigResult* c) { return !c->heat_map.empty(); }))
            return;
        put("<h3>Where the images differ</h3>\n<div class=\"figures\">\n");
        for (const ConfigResult* c : g.configs) {
            if (c->heat_map.empty()) continue;
            put("<figure><a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\" loading=\"lazy\"></a>"
                "<figcaption>{1}: max |error| {2}, fail {3}</figcaption></figure>\n",
                url(c->heat_map), escape(label(*c)), error_text(c->error.max_abs),
                share_text(c->error.fail_share));
        }
        put("</div>\n<p class=\"muted\">Each pixel's largest channel |difference| from the "
            "reference, log scale:</p>\n{}\n",
            heat_legend_svg(results_.thresholds, id));
    }

    void gpu_time(const Group& g) {
        bool any = false;
        for (const ConfigResult* c : g.configs) {
            if (c->gpu_passes.empty()) continue;
            if (!any) put("<h3>Where the GPU time goes</h3>\n");
            any = true;
            double total = c->gpu_total_ms;
            if (!(total > 0))
                for (const PassTime& p : c->gpu_passes) total += p.milliseconds;
            put("<details><summary>{}: {} ms on the GPU in {} passes</summary>\n<table>\n"
                "<tr><th>Pass</th><th class=\"num\">GPU ms</th><th class=\"num\">Share</th>"
                "<th></th></tr>\n",
                escape(label(*c)), ms_text(total), c->gpu_passes.size());
            for (const PassTime& p : c->gpu_passes) {
                const double share = total > 0 ? p.milliseconds / total : 0;
                put("<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td>"
                    "<span class=\"bar\" style=\"width:{:.0f}px\"></span></td></tr>\n",
                    escape(p.name), ms_text(p.milliseconds), share_text(share),
                    std::clamp(share, 0.0, 1.0) * 240);
            }
            put("</table>\n</details>\n");
        }
    }

    static std::string ratios(double tool, double acetate) {
        if (!(tool > 0) || !(acetate > 0)) return "—";
        return fmt::format("{:.2f}× / {:.2f}×", tool / acetate, acetate / tool);
    }

    void peers() {
        if (results_.peers.empty()) return;
        put("<section id=\"peers\">\n<h2>Other tools</h2>\n<p class=\"muted\">The same "
            "flattening (no effects) done by another tool in the same run. Ratios are tool ÷ "
            "acetate / acetate ÷ tool: above 1 on the left, acetate is faster.</p>\n<table>\n"
            "<tr><th>Scene</th><th>Tool</th><th>Command</th><th class=\"num\">Tool ms</th>"
            "<th class=\"num\">Tool --over ms</th><th class=\"num\">acetate frame ms</th>"
            "<th class=\"num\">acetate run ms</th><th class=\"num\">Whole runs</th>"
            "<th class=\"num\">Compositing (--over ÷ frame)</th><th>Difference</th>"
            "<th>Note</th></tr>\n");
        for (const PeerComparison& p : results_.peers) {
            const ErrorStats& d = p.difference;
            put("<tr><td>{}</td><td>{}</td><td><code>{}</code></td><td class=\"num\">{}</td>"
                "<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                "<td class=\"num\">{}</td><td class=\"num\">{}</td><td>max {}, mean {}, PSNR {}, "
                "fail {}{}</td><td>{}</td></tr>\n",
                escape(p.scene), escape(p.tool), escape(p.command), ms_text(p.tool_ms),
                ms_text(p.tool_over_ms), ms_text(p.acetate_frame_ms), ms_text(p.acetate_run_ms),
                ratios(p.tool_ms, p.acetate_run_ms), ratios(p.tool_over_ms, p.acetate_frame_ms),
                error_text(d.max_abs), error_text(d.mean_abs), psnr_text(d.psnr_db),
                share_text(d.fail_share), d.finite ? "" : ", <strong>not finite</strong>",
                escape(p.note));
        }
        put("</table>\n</section>\n");
    }

    static std::string ratio(double a, double b) {
        return a > 0 && b > 0 ? fmt::format("{:.2f}×", a / b) : "—";
    }

    void limits() {
        if (results_.limits.empty()) return;
        put("<section id=\"limits\">\n<h2>The frame against its limits</h2>\n<p class=\"muted\">"
            "Each scene as given (its presets, rgba16f), measured first in the run. Pixels "
            "shaded against the fewest any renderer must shade (Compositor::necessary_pixels); "
            "the first frame after load and after a floor switch against steady frames.</p>\n"
            "<table>\n<tr><th>Scene</th><th class=\"num\">Floor</th><th class=\"num\">Pixels "
            "shaded</th><th class=\"num\">Necessary</th><th class=\"num\">Shaded ÷ "
            "necessary</th><th class=\"num\">First frame ms</th><th class=\"num\">Steady ms</th>"
            "<th class=\"num\">First ÷ steady</th><th class=\"num\">Switch to</th>"
            "<th class=\"num\">After switch ÷ steady</th></tr>\n");
        for (const FrameLimits& l : results_.limits)
            put("<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                "<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                "<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                "<td class=\"num\">{}</td></tr>\n",
                escape(l.scene), l.floor, count_text(l.pixels_shaded),
                count_text(l.necessary_pixels),
                ratio(double(l.pixels_shaded), double(l.necessary_pixels)),
                ms_text(l.first_frame_ms), ms_text(l.steady_ms),
                ratio(l.first_frame_ms, l.steady_ms),
                l.switch_floor < 0 ? std::string("—") : std::to_string(l.switch_floor),
                ratio(l.switch_ms, l.switch_steady_ms));
        put("</table>\n</section>\n");
    }

    const BenchResults& results_;
    std::vector<Group> groups_;
    std::string out_;
};

}  // namespace

std::string render_html(const BenchResults& results) {
    return Page(results).render();
}

Result<void> write_html(const fs::path& directory, const BenchResults& results) {
    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot create the report folder: {}",
                                                     directory.string(), ec.message()));
    return write_file_atomically(directory / "index.html", render_html(results));
}

}  // namespace acetate::bench
