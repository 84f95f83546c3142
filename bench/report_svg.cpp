// The speed-against-error chart (report.hpp): inline SVG, for the page and as a file.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "report.hpp"
#include "report_text.hpp"

namespace acetate::bench {
namespace report_detail {
namespace {

// ---- The speed-against-error chart ----------------------------------------------------------

constexpr double kW = 760, kH = 420, kLeft = 100, kRight = 130, kTop = 48, kBottom = 52;
constexpr const char* kFrontColour = "#c2410c";
constexpr const char* kOtherColour = "#57606a";
constexpr const char* kOffColour = "#0969da";
constexpr const char* kGridColour = "#d0d7de";

// A linear axis over [lo, hi] padded by 8 %, with ticks at 1, 2 or 5 times a power of ten.
struct LinearAxis {
    double lo = 0, hi = 1, step = 1;
    LinearAxis(double min, double max) {
        const double pad = max > min ? (max - min) * 0.08 : std::max(std::fabs(max) * 0.1, 0.1);
        lo = (min >= 0 && min - pad < 0) ? 0 : min - pad;
        hi = max + pad;
        const double raw = (hi - lo) / 5, magnitude = std::pow(10.0, std::floor(std::log10(raw)));
        const double n = raw / magnitude;
        step = (n <= 1 ? 1 : n <= 2 ? 2 : n <= 5 ? 5 : 10) * magnitude;
        lo = std::floor(lo / step) * step;
        hi = std::ceil(hi / step) * step;
    }
    double x(double v) const { return kLeft + (v - lo) / (hi - lo) * (kW - kLeft - kRight); }
    int decimals() const { return std::max(0, -int(std::floor(std::log10(step) + 1e-9))); }
};

// A log10 axis over whole decades, with a floor row for error 0 (log10 cannot show it) and a
// ceiling row for non-finite errors, each apart from the decades.
struct ErrorAxis {
    int lo = -6, hi = 0;
    bool zero_row = false, non_finite_row = false;
    double top = kTop, bottom = kH - kBottom;  // the decades' extent
    explicit ErrorAxis(const std::vector<double>& errors) {
        double min = INFINITY, max = 0;
        for (double e : errors) {
            if (e == 0) zero_row = true;
            if (!std::isfinite(e)) non_finite_row = true;
            if (std::isfinite(e) && e > 0) min = std::min(min, e), max = std::max(max, e);
        }
        if (max > 0) {
            lo = int(std::floor(std::log10(min)));
            hi = std::max(lo + 1, int(std::ceil(std::log10(max))));
        }
        if (non_finite_row) top += 36;
        if (zero_row) bottom -= 28;
    }
    double zero_y() const { return kH - kBottom - 8; }
    double non_finite_y() const { return kTop + 8; }
    double y(double e) const {
        if (e == 0) return zero_y();
        if (!std::isfinite(e)) return non_finite_y();
        return bottom - (std::log10(e) - lo) / (hi - lo) * (bottom - top);
    }
};

// Places point labels greedily: right above, right below, left above, left below, each taken
// only if it overlaps no label placed before; crowded points fall back to moving down.
class LabelPlacer {
  public:
    std::string place(double x, double y, const std::string& text) {
        const double w = 6.2 * double(utf8_length(text)), h = 12;
        const std::pair<double, double> tries[] = {{7, -6}, {7, 14}, {-7, -6}, {-7, 14}};
        for (int shift = 0;; shift += 12) {
            for (auto [dx, dy] : tries) {
                const double left = dx > 0 ? x + dx : x + dx - w, base = y + dy + shift;
                const Box box{left, base - h + 2, left + w, base + 2};
                if (left < 0 || box.right > kW || overlaps(box)) continue;
                taken_.push_back(box);
                return fmt::format(R"(<text x="{:.1f}" y="{:.1f}">{}</text>)", left, base,
                                   escape(text));
            }
            if (shift > 120) return {};  // nowhere: the table names every point anyway
        }
    }

  private:
    struct Box {
        double left, top, right, bottom;
    };
    static size_t utf8_length(const std::string& s) {
        return size_t(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xc0) != 0x80; }));
    }
    bool overlaps(const Box& b) const {
        return std::any_of(taken_.begin(), taken_.end(), [&](const Box& t) {
            return b.left < t.right && t.left < b.right && b.top < t.bottom && t.top < b.bottom;
        });
    }
    std::vector<Box> taken_;
};

}  // namespace

std::string chart_svg(const Group& group) {
    std::vector<double> xs, errors;
    std::vector<const ConfigResult*> offs;
    for (const ConfigResult* c : group.configs) {
        if (!std::isfinite(c->median_ms)) continue;
        xs.push_back(c->median_ms);
        if (c->preset == "off") {
            offs.push_back(c);
            continue;
        }
        for (double v : {c->min_ms, c->max_ms})
            if (std::isfinite(v) && v > 0) xs.push_back(v);
        errors.push_back(c->error.finite ? c->error.mean_abs : INFINITY);
    }
    const std::string title = fmt::format("{} on {}", group.plugin, group.scene);
    std::string s = fmt::format(
        R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {0} {1}" width="{0}" height="{1}" )"
        R"(font-family="system-ui, sans-serif" font-size="11" fill="#1f2328">)"
        "\n<title>{2}: speed against error</title>\n"
        R"(<rect width="{0}" height="{1}" fill="#fff"/>)"
        "\n<text x=\"{3}\" y=\"16\" font-size=\"13\" font-weight=\"600\">{2}</text>\n",
        kW, kH, escape(title), kLeft);
    if (xs.empty())
        return s +
               fmt::format("<text x=\"{}\" y=\"{}\">No results.</text>\n</svg>\n", kLeft, kH / 2);
    const auto [min_x, max_x] = std::minmax_element(xs.begin(), xs.end());
    const LinearAxis ax(*min_x, *max_x);
    const ErrorAxis ay(errors);
    const double plot_top = kTop, plot_bottom = kH - kBottom;

    // Legend, frame, grid and axis labels.
    s += fmt::format(
        R"s(<g transform="translate({},34)"><circle cx="0" cy="-4" r="4.5" fill="{}"/>)s"
        R"(<text x="9" y="0">Pareto front</text><circle cx="100" cy="-4" r="4.5" fill="#fff" )"
        R"(stroke="{}" stroke-width="1.5"/><text x="109" y="0">dominated</text>)"
        R"(<line x1="190" y1="-9" x2="190" y2="1" stroke="{}" stroke-dasharray="4 3"/>)"
        R"(<text x="197" y="0">without the effect</text></g>)"
        "\n",
        kLeft, kFrontColour, kOtherColour, kOffColour);
    s += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="{}"/>)"
                     "\n",
                     kLeft, plot_top, kW - kLeft - kRight, plot_bottom - plot_top, kGridColour);
    for (double v = ax.lo; v <= ax.hi + ax.step / 2; v += ax.step)
        s += fmt::format(
            R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="{3}" stroke-width="0.5"/>)"
            R"(<text x="{0:.1f}" y="{4}" text-anchor="middle">{5:.{6}f}</text>)"
            "\n",
            ax.x(v), plot_top, plot_bottom, kGridColour, plot_bottom + 15, v, ax.decimals());
    const int every = ay.hi - ay.lo > 8 ? 2 : 1;
    for (int d = ay.lo; d <= ay.hi; d += every)
        s += fmt::format(
            R"(<line x1="{0}" y1="{1:.1f}" x2="{2}" y2="{1:.1f}" stroke="{3}" stroke-width="0.5"/>)"
            R"(<text x="{4}" y="{5:.1f}" text-anchor="end">{6}</text>)"
            "\n",
            kLeft, ay.y(std::pow(10.0, d)), kW - kRight, kGridColour, kLeft - 6,
            ay.y(std::pow(10.0, d)) + 4, d == 0 ? "1" : fmt::format("1e{}", d));
    auto row = [&](double y, double separator, const char* text) {
        s += fmt::format(
            R"(<line x1="{0}" y1="{1:.1f}" x2="{2}" y2="{1:.1f}" stroke="{3}" stroke-dasharray="2 3"/>)"
            R"(<text x="{4}" y="{5:.1f}" text-anchor="end">{6}</text>)"
            "\n",
            kLeft, separator, kW - kRight, kOtherColour, kLeft - 6, y + 4, text);
    };
    if (ay.zero_row) row(ay.zero_y(), ay.bottom + 14, "0 (reference)");
    if (ay.non_finite_row) row(ay.non_finite_y(), ay.top - 18, "not finite");
    s += fmt::format(
        R"(<text x="{:.1f}" y="{}" text-anchor="middle">median frame time (ms); whiskers: min–max</text>)"
        R"s(<text transform="translate(16,{:.1f}) rotate(-90)" text-anchor="middle">mean |error| (log scale)</text>)s"
        "\n",
        (kLeft + kW - kRight) / 2, kH - 14, (plot_top + plot_bottom) / 2);

    // "off": where the frame time would be without the effect.
    for (size_t k = 0; k < offs.size(); ++k) {
        const double x = ax.x(offs[k]->median_ms);
        const std::string text =
            offs.size() > 1 ? "without the effect (" + offs[k]->format + ")" : "without the effect";
        s += fmt::format(
            R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="{3}" stroke-dasharray="6 4"/>)"
            R"(<text x="{4:.1f}" y="{5}" fill="{3}">{6}</text>)"
            "\n",
            x, plot_top, plot_bottom, kOffColour, x + 4, plot_top + 12 + 13 * double(k),
            escape(text));
    }

    // Whiskers, the front's polyline, then the points on top with their labels.
    struct Dot {
        const ConfigResult* c;
        double x, y;
        bool front;
    };
    std::vector<Dot> dots;
    for (size_t i = 0; i < group.configs.size(); ++i) {
        const ConfigResult* c = group.configs[i];
        if (c->preset == "off" || !std::isfinite(c->median_ms)) continue;
        dots.push_back({c, ax.x(c->median_ms), ay.y(c->error.finite ? c->error.mean_abs : INFINITY),
                        bool(group.front[i])});
        if (std::isfinite(c->min_ms) && std::isfinite(c->max_ms) && c->max_ms > c->min_ms)
            s += fmt::format(
                R"(<path d="M{0:.1f} {2:.1f}H{1:.1f}M{0:.1f} {3:.1f}v6M{1:.1f} {3:.1f}v6" )"
                R"(stroke="{4}" fill="none"/>)"
                "\n",
                ax.x(c->min_ms), ax.x(c->max_ms), dots.back().y, dots.back().y - 3, kOtherColour);
    }
    std::vector<Dot> front;
    std::copy_if(dots.begin(), dots.end(), std::back_inserter(front),
                 [](const Dot& d) { return d.front; });
    std::sort(front.begin(), front.end(), [](const Dot& a, const Dot& b) {
        return std::pair(a.x, -a.y) < std::pair(b.x, -b.y);
    });
    if (front.size() > 1) {
        std::string points;
        for (const Dot& d : front) points += fmt::format("{:.1f},{:.1f} ", d.x, d.y);
        s += fmt::format(
            R"(<polyline points="{}" fill="none" stroke="{}" stroke-width="2" opacity="0.7"/>)"
            "\n",
            points, kFrontColour);
    }
    LabelPlacer labels;
    for (const Dot& d : dots)
        s += fmt::format(
            R"(<circle cx="{:.1f}" cy="{:.1f}" r="4.5" fill="{}" stroke="{}" stroke-width="1.5">)"
            "<title>{}: {} ms, mean |error| {}</title></circle>\n",
            d.x, d.y, d.front ? kFrontColour : "#fff", d.front ? kFrontColour : kOtherColour,
            escape(label(*d.c)), ms_text(d.c->median_ms), error_text(d.c->error.mean_abs));
    for (const Dot& d : dots) s += labels.place(d.x, d.y, label(*d.c)) + "\n";
    return s + "</svg>\n";
}

}  // namespace report_detail

std::string speed_error_svg(const BenchResults& results, const std::string& scene,
                            const std::string& plugin) {
    using namespace report_detail;
    for (const Group& g : groups_of(results))
        if (g.scene == scene && g.plugin == plugin) return chart_svg(g);
    return chart_svg(Group{scene, plugin, {}, {}});
}

}  // namespace acetate::bench
