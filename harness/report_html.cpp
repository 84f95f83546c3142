// index.html for a validation or fuzz run (report.hpp): one self-contained page.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <set>

#include "core/atomic_file.hpp"
#include "report.hpp"

namespace acetate::harness {
namespace fs = std::filesystem;

// ---- HTML -----------------------------------------------------------------------------------
// One self-contained page: inline CSS and a few lines of script, no external resources apart
// from the report's own images. Everything shown comes from the plugin or its child processes
// (ids, messages, logs), so every piece of text goes through escape() or url().

namespace {

constexpr size_t kMaxExamplesShown = 10;

constexpr std::string_view kStyle = R"css(
:root { --pass: #1a7f37; --skip: #6e7781; --warn: #b7791f; --fail: #cf222e;
        --timeout: #8b1a1a; --crash: #6f42c1; --line: #d0d7de; --muted: #57606a;
        --panel: #f6f8fa; }
* { box-sizing: border-box; }
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: #1f2328;
       max-width: 1280px; margin: 0 auto; padding: 24px; }
h1 { font-size: 24px; margin: 0 0 2px; }
h2 { font-size: 18px; margin: 32px 0 8px; padding-bottom: 4px; border-bottom: 1px solid var(--line); }
h3 { font-size: 14px; margin: 16px 0 4px; }
a { color: #0969da; text-decoration: none; } a:hover { text-decoration: underline; }
code, pre { font: 12.5px/1.4 ui-monospace, SFMono-Regular, Menlo, Consolas, monospace; }
pre { background: var(--panel); border: 1px solid var(--line); border-radius: 6px; padding: 8px 12px;
      margin: 6px 0; white-space: pre-wrap; overflow-wrap: anywhere; }
table { border-collapse: collapse; width: 100%; margin: 6px 0 12px; }
th, td { text-align: left; vertical-align: top; padding: 4px 8px; border-bottom: 1px solid var(--line); }
th { background: var(--panel); font-weight: 600; white-space: nowrap; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.mono { font-family: ui-monospace, SFMono-Regular, Menlo, Consolas, monospace; font-size: 12.5px;
          white-space: nowrap; }
table.examples { width: auto; font-size: 13px; }
.subtitle, .muted { color: var(--muted); }
.badge { display: inline-block; min-width: 64px; padding: 1px 8px; border-radius: 10px; color: #fff;
         font-size: 12px; font-weight: 600; letter-spacing: .03em; text-align: center; }
.PASS { background: var(--pass); } .SKIP { background: var(--skip); } .WARN { background: var(--warn); }
.FAIL { background: var(--fail); } .FLAKY { background: var(--fail); }
.WAIVED { background: var(--warn); }
.TIMEOUT { background: var(--timeout); }
.CRASH { background: var(--crash); }
.status { font-size: 16px; font-weight: 600; padding: 8px 12px; border-radius: 6px; margin: 12px 0;
          color: #fff; }
dl.facts { display: grid; grid-template-columns: max-content 1fr; gap: 2px 16px; margin: 12px 0; }
dl.facts dt { color: var(--muted); } dl.facts dd { margin: 0; overflow-wrap: anywhere; }
.error { background: #ffebe9; border: 1px solid var(--fail); color: #82071e; border-radius: 6px;
         padding: 8px 12px; margin: 12px 0; white-space: pre-wrap; }
details.case { border: 1px solid var(--line); border-radius: 6px; margin: 8px 0; }
details.case > summary { padding: 6px 12px; cursor: pointer; background: var(--panel);
                         border-radius: 6px; }
details.case[open] > summary { border-bottom: 1px solid var(--line); border-radius: 6px 6px 0 0; }
details.case > summary .case-id { font-weight: 600; margin: 0 8px; }
.case-body { padding: 4px 12px 12px; }
.figures { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; margin: 8px 0; }
figure { margin: 0; }
figure img { display: block; image-rendering: pixelated; min-width: 96px; min-height: 96px;
             max-width: 384px; max-height: 384px; border: 1px solid var(--line);
             background: repeating-conic-gradient(#c8c8c8 0% 25%, #fff 0% 50%) 0 0 / 16px 16px; }
figcaption { font-size: 12px; color: var(--muted); margin-top: 2px; max-width: 384px;
             overflow-wrap: anywhere; }
)css";

// Opening a link to something inside a collapsed case opens the case first.
constexpr std::string_view kScript = R"js(
function openTarget() {
  var target = document.getElementById(decodeURIComponent(location.hash.slice(1)));
  for (var e = target; e; e = e.parentElement) if (e.tagName === 'DETAILS') e.open = true;
  if (target) target.scrollIntoView();
}
addEventListener('hashchange', openTarget);
addEventListener('DOMContentLoaded', openTarget);
)js";

// Text safe in element content and in quoted attributes. Control characters (a log's colour
// codes, NULs) are dropped: HTML cannot show them and some are parse errors.
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
            case '\t':
            case '\n':
            case '\r':
                out += c;
                break;
            default:
                if ((unsigned char)c >= 0x20 && c != 0x7f) out += c;
        }
    }
    return out;
}

// A relative image path as a URL: bytes outside the unreserved set are percent-encoded, so a
// '#', '?' or space in a file name still finds the file, and no path can turn into a scheme
// ("javascript:...") or break out of the attribute.
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

std::string slug(std::string_view text) {
    std::string out;
    for (unsigned char c : text) out += std::isalnum(c) ? char(c) : '-';
    return out.empty() ? "-" : out;
}

// Anchor ids, unique on the page: "sizes/1x1" and "sizes.1x1" both slug to "sizes-1x1", so a
// later one becomes "sizes-1x1-2".
class Anchors {
  public:
    std::string claim(const std::string& wanted) {
        std::string id = wanted;
        for (int n = 2; !taken_.insert(id).second; ++n) id = fmt::format("{}-{}", wanted, n);
        return id;
    }

  private:
    std::set<std::string> taken_;
};

std::string badge(Verdict verdict) {
    return fmt::format(R"(<span class="badge {0}">{0}</span>)", to_string(verdict));
}

std::string yes_no(bool value) {
    return value ? R"(<span class="badge PASS">yes</span>)"
                 : R"(<span class="badge SKIP">no</span>)";
}

std::string number_text(double value) {
    if (std::isnan(value)) return std::string(kNaN);
    if (std::isinf(value)) return std::string(value > 0 ? kInfinity : kMinusInfinity);
    return fmt::format("{:.6g}", value);
}

std::string rgba_text(const std::array<float, 4>& rgba) {
    return fmt::format("({}, {}, {}, {})", number_text(rgba[0]), number_text(rgba[1]),
                       number_text(rgba[2]), number_text(rgba[3]));
}

std::string seconds_text(double seconds) {
    return std::isfinite(seconds) ? fmt::format("{:.2f} s", seconds) : number_text(seconds);
}

// "12 PASS · 1 FAIL", most severe last, as the verdicts are ordered.
template <class Counts, class Name>
std::string counts_text(const Counts& counts, Name name) {
    std::vector<std::string> parts;
    for (Verdict verdict : kVerdicts)
        if (auto it = counts.find(name(verdict)); it != counts.end() && it->second > 0)
            parts.push_back(fmt::format("{} {}", it->second, to_string(verdict)));
    return parts.empty() ? "none" : fmt::format("{}", fmt::join(parts, " · "));
}

// The page's anchors, decided before any of it is written so the summary can link forward.
struct PageAnchors {
    std::vector<std::string> cases;                   // by index in report.cases
    std::vector<std::vector<std::string>> checks;     // [case][check]
    std::map<std::string, std::string> summary_link;  // check name -> the row explaining it
};

PageAnchors plan_anchors(const ValidationReport& report,
                         const std::vector<CheckSummary>& summaries) {
    Anchors anchors;
    for (const char* section : {"report", "stages", "summary", "cases", "history"})
        anchors.claim(section);
    PageAnchors page;
    for (const CaseResult& result : report.cases) {
        page.cases.push_back(anchors.claim(slug(result.id)));
        std::vector<std::string>& checks = page.checks.emplace_back();
        for (const CheckResult& check : result.checks)
            checks.push_back(anchors.claim(page.cases.back() + "--" + slug(check.check)));
    }
    // Each summary row links to the first case that gave the check its overall verdict; the
    // process pseudo-check to the first crashed or timed-out case, else to the case list.
    for (const CheckSummary& summary : summaries) {
        std::string& link = page.summary_link[summary.check];
        for (size_t i = 0; i < report.cases.size() && link.empty(); ++i) {
            const CaseResult& result = report.cases[i];
            if (summary.check == kProcessCheck) {
                if (result.verdict == summary.verdict && is_process_failure(result.verdict))
                    link = page.cases[i];
                continue;
            }
            for (size_t k = 0; k < result.checks.size() && link.empty(); ++k)
                if (result.checks[k].check == summary.check &&
                    result.checks[k].verdict == summary.verdict)
                    link = page.checks[i][k];
        }
        if (link.empty()) link = "cases";
    }
    return page;
}

class HtmlPage {
  public:
    explicit HtmlPage(const ValidationReport& report)
        : report_(report),
          summaries_(summarize_checks(report)),
          anchors_(plan_anchors(report, summaries_)) {}

    std::string render() {
        head();
        header();
        stages();
        summary();
        inputs();
        cases();
        history();
        out_ += "</body>\n</html>\n";
        return std::move(out_);
    }

  private:
    template <class... Args>
    void put(fmt::format_string<Args...> format, Args&&... args) {
        fmt::format_to(std::back_inserter(out_), format, std::forward<Args>(args)...);
    }

    std::string plugin_title() const {
        const std::string& name = report_.display_name.empty() ? report_.id : report_.display_name;
        return name.empty() ? report_.plugin_file : name;
    }

    void head() {
        put("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            "<title>{} {} — {}</title>\n<style>{}</style>\n<script>{}</script>\n</head>\n"
            "<body id=\"report\">\n",
            escape(plugin_title()), escape(report_.version),
            run_failed(report_) ? "FAILED" : "PASSED", kStyle, kScript);
    }

    void fact(std::string_view name, const std::string& value) {
        put("<dt>{}</dt><dd>{}</dd>\n", name, value.empty() ? "—" : escape(value));
    }

    void header() {
        put("<header>\n<h1>{}</h1>\n<div class=\"subtitle\">{} {}</div>\n", escape(plugin_title()),
            escape(report_.id), escape(report_.version));
        const bool failed = run_failed(report_);
        put("<div class=\"status {}\">{} · {} cases: {}</div>\n", failed ? "FAIL" : "PASS",
            failed ? "FAILED" : "PASSED", report_.cases.size(),
            counts_text(count_verdicts(report_), [](Verdict v) { return to_string(v); }));
        if (!report_.error.empty()) put("<div class=\"error\">{}</div>\n", escape(report_.error));
        put("<dl class=\"facts\">\n");
        fact("Plugin file", report_.plugin_file);
        fact("Scope", report_.scope);
        fact("Coverage", report_.coverage);
        fact("Binary SHA-256", report_.binary_sha256);
        fact("Source digest", report_.source_digest);
        fact("Harness version", report_.harness_version);
        fact("Started at", report_.started_at);
        fact("Duration", seconds_text(report_.seconds));
        fact("Strictness", std::to_string(report_.strictness));
        if (!report_.combinations.empty()) fact("Combinations", report_.combinations);
        fact("Seed", std::to_string(report_.seed));
        fact("Registry stage",
             fmt::format("{} → {}", report_.stage_before.empty() ? "—" : report_.stage_before,
                         report_.stage_after.empty() ? "—" : report_.stage_after));
        put("</dl>\n</header>\n");
    }

    void stages() {
        put("<section id=\"stages\">\n<h2>Stages</h2>\n");
        if (report_.stages.empty()) {
            put("<p class=\"muted\">No automated stage was attempted.</p>\n</section>\n");
            return;
        }
        put("<table>\n<tr><th>Stage</th><th>Passed</th><th>Recorded</th><th>Note</th></tr>\n");
        for (const StageRun& run : report_.stages)
            put("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", escape(run.stage),
                yes_no(run.passed), yes_no(run.recorded), escape(run.note));
        put("</table>\n</section>\n");
    }

    void summary() {
        put("<section id=\"summary\">\n<h2>Checks</h2>\n");
        if (summaries_.empty()) {
            put("<p class=\"muted\">No case ran.</p>\n</section>\n");
            return;
        }
        put("<table>\n<tr><th>Check</th><th>Verdict</th><th>Cases</th><th>First failure</th>"
            "</tr>\n");
        for (const CheckSummary& s : summaries_)
            put("<tr><td><a href=\"#{}\">{}</a></td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                escape(anchors_.summary_link.at(s.check)), escape(s.check), badge(s.verdict),
                counts_text(s.cases, [](Verdict v) { return v; }), escape(s.first_failure));
        put("</table>\n</section>\n");
    }

    // The input model: per dimension, every value some case tried, with how many cases and the
    // worst verdict among them, so a reader sees what was explored and where it failed.
    void inputs() {
        const auto tried = summarize_inputs(report_);
        if (tried.empty()) return;
        put("<section id=\"inputs\">\n<h2>Inputs tried</h2>\n<table>\n<tr><th>Dimension</th>"
            "<th>Values (cases)</th></tr>\n");
        for (const auto& [dimension, values] : tried) {
            std::string cells;
            for (const auto& [value, summary] : values)
                cells += fmt::format(
                    "{}{} ({}{})", cells.empty() ? "" : " · ", escape(value), summary.cases,
                    is_failing(summary.worst) ? fmt::format(", {}", badge(summary.worst))
                                              : std::string());
            put("<tr><td>{}</td><td>{}</td></tr>\n", escape(dimension), cells);
        }
        put("</table>\n</section>\n");
    }

    // Failing cases first, open; the rest in run order, collapsed unless they warn, so a run of
    // hundreds of passing cases stays one screen of summaries.
    void cases() {
        put("<section id=\"cases\">\n<h2>Cases</h2>\n");
        if (report_.cases.empty()) put("<p class=\"muted\">No case ran.</p>\n");
        std::vector<size_t> order(report_.cases.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::stable_partition(order.begin(), order.end(),
                              [&](size_t i) { return is_failing(report_.cases[i].verdict); });
        for (size_t i : order) one_case(i);
        put("</section>\n");
    }

    void one_case(size_t index) {
        const CaseResult& c = report_.cases[index];
        const bool open = is_failing(c.verdict) || c.verdict == Verdict::Warn;
        put("<details class=\"case\" id=\"{}\"{}>\n<summary>{}<span class=\"case-id\">{}</span>"
            "<span class=\"muted\">{}</span></summary>\n<div class=\"case-body\">\n",
            escape(anchors_.cases[index]), open ? " open" : "", badge(c.verdict), escape(c.id),
            escape(c.description));
        put("<p class=\"muted\">seed {} · {}{}</p>\n", c.seed, seconds_text(c.seconds),
            c.output_digest.empty()
                ? ""
                : fmt::format(" · output digest <code>{}</code>", escape(c.output_digest)));
        if (!c.message.empty()) put("<p>{}</p>\n", escape(c.message));
        if (!c.reproduce.empty())
            put("<h3>Reproduce</h3>\n<pre><code>{}</code></pre>\n", escape(c.reproduce));
        checks_table(index);
        for (const CheckResult& check : c.checks) examples(check);
        figures(c);
        if (!c.log.empty())
            put("<details><summary>Log</summary>\n<pre>{}</pre>\n</details>\n", escape(c.log));
        put("</div>\n</details>\n");
    }

    void checks_table(size_t index) {
        const CaseResult& c = report_.cases[index];
        if (c.checks.empty()) return;
        put("<table>\n<tr><th>Check</th><th>Verdict</th><th>Message</th>"
            "<th class=\"num\">Violations</th></tr>\n");
        for (size_t k = 0; k < c.checks.size(); ++k) {
            const CheckResult& check = c.checks[k];
            put("<tr id=\"{}\"><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{}</td></tr>\n",
                escape(anchors_.checks[index][k]), escape(check.check), badge(check.verdict),
                escape(check.message), check.violations);
        }
        put("</table>\n");
    }

    void examples(const CheckResult& check) {
        if (check.examples.empty()) return;
        const size_t shown = std::min(check.examples.size(), kMaxExamplesShown);
        const uint64_t total = std::max<uint64_t>(check.violations, check.examples.size());
        put("<h3>{}: {} of {} offending pixels</h3>\n<table class=\"examples\">\n"
            "<tr><th class=\"num\">x</th><th class=\"num\">y</th><th>Floor</th>"
            "<th>Input rgba</th><th>Output rgba</th><th>What</th></tr>\n",
            escape(check.check), shown, total);
        for (size_t i = 0; i < shown; ++i) {
            const Violation& v = check.examples[i];
            put("<tr><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td>"
                "<td class=\"mono\">{}</td><td class=\"mono\">{}</td><td>{}</td></tr>\n",
                v.x, v.y, v.floor < 0 ? "composite" : std::to_string(v.floor), rgba_text(v.input),
                rgba_text(v.output), escape(v.what));
        }
        put("</table>\n");
    }

    void figure(const std::string& path, const std::string& caption) {
        put("<figure><a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\" loading=\"lazy\"></a>"
            "<figcaption>{1}</figcaption></figure>\n",
            url(path), escape(caption));
    }

    void figures(const CaseResult& c) {
        const bool any = !c.images.empty() || std::any_of(c.checks.begin(), c.checks.end(),
                                                          [](const CheckResult& check) {
                                                              return !check.images.empty();
                                                          });
        if (!any) return;
        put("<div class=\"figures\">\n");
        for (const auto& [role, path] : c.images) figure(path, role);
        for (const CheckResult& check : c.checks)
            for (const auto& [role, path] : check.images)
                figure(path, fmt::format("{}: {}", check.check, role));
        put("</div>\n");
    }

    void history() {
        put("<section id=\"history\">\n<h2>History</h2>\n");
        if (report_.history.empty()) {
            put("<p class=\"muted\">The registry has no history for this plugin.</p>\n"
                "</section>\n");
            return;
        }
        put("<table>\n<tr><th>At</th><th>What</th><th>By</th><th>Notes</th></tr>\n");
        for (const HistoryLine& line : report_.history)
            put("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", escape(line.at),
                escape(line.what), escape(line.by), escape(line.notes));
        put("</table>\n</section>\n");
    }

    const ValidationReport& report_;
    std::vector<CheckSummary> summaries_;
    PageAnchors anchors_;
    std::string out_;
};

}  // namespace

Result<void> write_html_report(const ValidationReport& report, const fs::path& directory) {
    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot create the report directory: {}",
                                                     directory.string(), ec.message()));
    return write_file_atomically(directory / "index.html", HtmlPage(report).render());
}

}  // namespace acetate::harness
