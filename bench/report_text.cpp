#include "report_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "image_compare.hpp"

namespace acetate::bench::report_detail {

// Text safe in element content and quoted attributes, in HTML and in SVG (XML). Control
// characters are dropped: neither can show them and in XML they are errors.
std::string escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                if ((unsigned char)c >= 0x20 && c != 0x7f) out += c;
        }
    }
    return out;
}

// A relative file name as a URL: everything outside the unreserved set is percent-encoded, so a
// name can neither become a scheme ("javascript:") nor leave the attribute.
std::string url(std::string_view path) {
    std::string out;
    for (unsigned char c : path) {
        if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/')
            out += char(c);
        else
            out += fmt::format("%{:02X}", c);
    }
    return out;
}

std::string ms_text(double ms) {
    if (!std::isfinite(ms)) return "—";
    const double a = std::fabs(ms);
    return fmt::format("{:.{}f}", ms, a >= 100 ? 0 : a >= 10 ? 1 : a >= 1 ? 2 : 3);
}
std::string error_text(double value) {
    if (std::isnan(value)) return "—";
    if (std::isinf(value)) return value > 0 ? "∞" : "−∞";
    return value == 0 ? "0" : fmt::format("{:.3g}", value);
}
std::string psnr_text(double db) {
    return std::isfinite(db) ? fmt::format("{:.1f} dB", db) : error_text(db);
}
std::string share_text(double share) {
    return std::isfinite(share) ? fmt::format("{:.3g} %", share * 100.0) : error_text(share);
}
// 2073600 as "2 073 600" (narrow no-break spaces): pixel counts are read by their size.
std::string count_text(uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += "\u202f";
        out += digits[i];
    }
    return out;
}
std::string label(const ConfigResult& c) {
    return c.preset + " · " + c.format;
}

std::vector<Group> groups_of(const BenchResults& results) {
    std::vector<Group> groups;
    for (const ConfigResult& c : results.configs) {
        auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
            return g.scene == c.scene && g.plugin == c.plugin;
        });
        if (it == groups.end()) it = groups.insert(groups.end(), Group{c.scene, c.plugin, {}, {}});
        it->configs.push_back(&c);
    }
    for (Group& g : groups) {
        std::vector<std::pair<double, double>> points;
        for (const ConfigResult* c : g.configs) {
            const bool eligible =
                c->preset != "off" && c->error.finite && std::isfinite(c->error.mean_abs);
            points.emplace_back(eligible ? c->median_ms : NAN, c->error.mean_abs);
        }
        g.front = pareto_front(points);
    }
    return groups;
}

}  // namespace acetate::bench::report_detail
