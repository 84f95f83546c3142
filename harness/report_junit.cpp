// junit.xml (report_junit.hpp): a validation run in the JUnit XML dialect CI servers read.
// Everything in it but the numbers comes from the plugin or its child processes, so every
// piece of text goes through escape(), and every time through seconds_attribute().

#include "report_junit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string_view>
#include <utility>

#include "core/atomic_file.hpp"

namespace acetate::harness {
namespace {

constexpr std::array<const char*, 2> kStages = {"ALPHA_TESTED", "INTEGRATED"};

// The validation stage a case is evidence for: the integration cases (a real stack, other
// plugins around it; ids "integration/...") record INTEGRATED, every other case ALPHA_TESTED.
std::string_view stage_of(const CaseResult& c) {
    return c.id.starts_with("integration/") ? "INTEGRATED" : "ALPHA_TESTED";
}

// ---- text -----------------------------------------------------------------------------------

// Code points XML 1.0 allows in a document (its production "Char").
bool xml_char(char32_t c) {
    return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) ||
           (c >= 0xE000 && c <= 0xFFFD) || (c >= 0x10000 && c <= 0x10FFFF);
}

// The length of the UTF-8 sequence at text[at], its code point in `c`; 0 when it is not valid
// UTF-8 (a bad or truncated sequence, an overlong form, a surrogate, past U+10FFFF).
size_t decode_utf8(std::string_view text, size_t at, char32_t& c) {
    const auto byte = [&](size_t i) { return static_cast<unsigned char>(text[i]); };
    const unsigned char lead = byte(at);
    c = lead;
    if (lead < 0x80) return 1;
    const size_t length = std::countl_one(lead);  // 110xxxxx: 2 bytes, ... 11110xxx: 4
    constexpr char32_t kLeast[] = {0, 0, 0x80, 0x800, 0x10000};
    if (length < 2 || length > 4 || at + length > text.size()) return 0;
    c = lead & (0x7F >> length);
    for (size_t i = at + 1; i < at + length; ++i) {
        if ((byte(i) & 0xC0) != 0x80) return 0;
        c = (c << 6) | (byte(i) & 0x3F);
    }
    return c < kLeast[length] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF) ? 0 : length;
}

// The reference for `c` if it needs one: the five special characters; tab and newline in
// attributes (parsers make literal ones spaces); carriage return anywhere (parsers drop it).
const char* xml_entity(char32_t c, bool attribute) {
    static constexpr std::pair<char32_t, const char*> kEntities[] = {
        {'&', "&amp;"},   {'<', "&lt;"},   {'>', "&gt;"},  {'"', "&quot;"},
        {'\'', "&apos;"}, {'\r', "&#13;"}, {'\t', "&#9;"}, {'\n', "&#10;"}};
    for (const auto& [character, entity] : kEntities)
        if (c == character) return attribute || (c != '\t' && c != '\n') ? entity : nullptr;
    return nullptr;
}

// Text safe in element content and quoted attributes. What XML 1.0 forbids (a log's colour
// codes, NULs) becomes "#x1B", as pytest writes it; a byte that is not UTF-8 becomes U+FFFD.
std::string escape(std::string_view text, bool attribute = false) {
    std::string out;
    out.reserve(text.size());
    for (size_t at = 0, length = 1; at < text.size(); at += length) {
        char32_t c = 0;
        length = decode_utf8(text, at, c);
        if (length == 0) {
            out += "\xEF\xBF\xBD";  // U+FFFD
            length = 1;
        } else if (const char* entity = xml_entity(c, attribute)) {
            out += entity;
        } else if (xml_char(c)) {
            out.append(text.substr(at, length));
        } else {
            out += fmt::format("#x{:02X}", uint32_t(c));
        }
    }
    return out;
}

std::string attr(std::string_view text) {
    return escape(text, true);
}

// "(r, g, b, a)", with NaN and the infinities by name as report.json writes them.
std::string rgba(const std::array<float, 4>& v) {
    const auto channel = [](float x) -> std::string {
        if (std::isnan(x)) return std::string(kNaN);
        return std::isinf(x) ? std::string(x > 0 ? kInfinity : kMinusInfinity)
                             : fmt::format("{}", x);
    };
    return fmt::format("({}, {}, {}, {})", channel(v[0]), channel(v[1]), channel(v[2]),
                       channel(v[3]));
}

// ` time="1.250"`, in the form the schema's SUREFIRE_TIME allows (digits, at most three
// decimals, no sign, no exponent); nothing for a negative or non-finite time.
std::string seconds_attribute(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) return "";
    return fmt::format(" time=\"{:.3f}\"", seconds == 0 ? 0.0 : seconds);  // never "-0.000"
}

// ---- one case -------------------------------------------------------------------------------

std::string pixel(const Violation& v) {
    return fmt::format("({}, {}) on floor {}{}: input rgba {} -> output rgba {}: {}", v.x, v.y,
                       v.floor, v.floor < 0 ? " (the composite)" : "", rgba(v.input),
                       rgba(v.output), v.what);
}

// "check: message", then its violation count and first example pixel when it has them.
std::string check_text(const CheckResult& c, std::string_view indent = "\n  ") {
    std::string out = fmt::format("{}: {}", c.check, c.message);
    if (c.violations > 0 || !c.examples.empty())
        out += fmt::format("{}{} violation{}", indent, c.violations, c.violations == 1 ? "" : "s");
    if (!c.examples.empty()) out += fmt::format(", the first at {}", pixel(c.examples.front()));
    return out;
}

// Each check whose verdict `wanted` accepts, one per line after `prefix`.
template <class Wanted>
std::string checks_text(const CaseResult& c, Wanted wanted, std::string_view prefix = "") {
    std::string out;
    for (const CheckResult& check : c.checks)
        if (wanted(check.verdict)) out += fmt::format("{}{}\n", prefix, check_text(check));
    return out;
}

auto verdict_is(Verdict wanted) {
    return [wanted](Verdict verdict) { return verdict == wanted; };
}

// One line for the message attribute: a crash's signal or a timeout's limit (the case's
// message), or a FAIL's first failing check (with its first example pixel) and how many more.
std::string summary(const CaseResult& c) {
    const auto failing = [](const CheckResult& check) { return is_failing(check.verdict); };
    const auto first = std::find_if(c.checks.begin(), c.checks.end(), failing);
    if ((c.verdict != Verdict::Fail && !c.message.empty()) || first == c.checks.end())
        return !c.message.empty() ? c.message : to_string(c.verdict);
    const auto more = std::count_if(first + 1, c.checks.end(), failing);
    if (more == 0) return check_text(*first, "; ");
    return fmt::format("{} (and {} more failing check{})", check_text(*first, "; "), more,
                       more == 1 ? "" : "s");
}

// The body of a <failure> or <error>: each failing check with its first example, then how
// to run the case again.
std::string details(const CaseResult& c) {
    std::string out;
    if (!c.description.empty()) out += c.description + "\n";
    if (!c.message.empty()) out += c.message + "\n";
    out += checks_text(c, is_failing);
    if (!c.reproduce.empty()) out += fmt::format("reproduce: {}\n", c.reproduce);
    return out;
}

std::string testcase(const CaseResult& c, const std::string& classname) {
    std::string body;
    if (is_failing(c.verdict)) {
        // A <failure>: the plugin's output is wrong; an <error>: its child process crashed or
        // ran out of time.
        body += fmt::format("      <{0} message=\"{1}\" type=\"{2}\">{3}</{0}>\n",
                            is_process_failure(c.verdict) ? "error" : "failure", attr(summary(c)),
                            to_string(c.verdict), escape(details(c)));
    } else if (c.verdict == Verdict::Skip) {
        std::string reason =
            !c.message.empty() ? c.message : checks_text(c, verdict_is(Verdict::Skip));
        if (reason.ends_with('\n')) reason.pop_back();
        body += reason.empty() ? "      <skipped/>\n"
                               : fmt::format("      <skipped message=\"{}\"/>\n", attr(reason));
    }
    std::string warnings = checks_text(c, verdict_is(Verdict::Warn), "warning: ") +
                           checks_text(c, verdict_is(Verdict::Waived), "waived: ");
    if (warnings.empty() && c.verdict == Verdict::Warn) warnings = c.message;
    if (!warnings.empty())
        body += fmt::format("      <system-out>{}</system-out>\n", escape(warnings));
    if (!c.log.empty()) body += fmt::format("      <system-err>{}</system-err>\n", escape(c.log));
    return fmt::format("    <testcase name=\"{}\" classname=\"{}\"{}{}", attr(c.id),
                       attr(classname), seconds_attribute(c.seconds),
                       body.empty() ? "/>\n" : ">\n" + body + "    </testcase>\n");
}

// ---- suites ---------------------------------------------------------------------------------

struct Totals {
    uint64_t tests = 0, failures = 0, errors = 0, skipped = 0;
    double seconds = 0;  // of the cases whose time is known

    void add(Verdict verdict, double case_seconds) {
        ++tests;
        failures += is_failing(verdict) && !is_process_failure(verdict);
        errors += is_process_failure(verdict);
        skipped += verdict == Verdict::Skip;
        if (std::isfinite(case_seconds) && case_seconds > 0) seconds += case_seconds;
    }
};

std::string plugin_name(const ValidationReport& r) {
    return !r.id.empty() ? r.id : !r.plugin_file.empty() ? r.plugin_file : "unknown-plugin";
}

std::string properties(const ValidationReport& r) {
    std::string out = "    <properties>\n";
    const auto property = [&out](const char* name, const std::string& value) {
        out += fmt::format("      <property name=\"{}\" value=\"{}\"/>\n", name, attr(value));
    };
    property("plugin_id", r.id);
    property("plugin_version", r.version);
    property("binary_sha256", r.binary_sha256);
    property("source_digest", r.source_digest);
    property("strictness", std::to_string(r.strictness));
    property("seed", std::to_string(r.seed));
    property("harness_version", r.harness_version);
    return out + "    </properties>\n";
}

std::string suite(const ValidationReport& r, std::string_view name, const Totals& t,
                  const std::string& testcases) {
    return fmt::format(
        "  <testsuite name=\"{} {}\" tests=\"{}\" failures=\"{}\" errors=\"{}\" skipped=\"{}\"{} "
        "timestamp=\"{}\">\n{}{}  </testsuite>\n",
        attr(plugin_name(r)), attr(name), t.tests, t.failures, t.errors, t.skipped,
        seconds_attribute(t.seconds), attr(r.started_at), properties(r), testcases);
}

}  // namespace

std::string junit_xml(const ValidationReport& report) {
    const std::string plugin = plugin_name(report);
    std::string suites;
    Totals all;
    if (!report.error.empty()) {
        // The run stopped before (or instead of) its cases: one errored testcase says why.
        Totals t;  // counted as a crashed case would be: one test, one error
        t.add(Verdict::Crash, 0);
        all.add(Verdict::Crash, 0);
        suites += suite(
            report, "validate", t,
            fmt::format("    <testcase name=\"validate\" classname=\"{}.validate\">\n"
                        "      <error message=\"{}\" type=\"ERROR\">the validation run could not "
                        "start or complete: {}\n</error>\n    </testcase>\n",
                        attr(plugin), attr(report.error), escape(report.error)));
    }
    for (const char* stage : kStages) {
        Totals t;
        std::string testcases;
        for (const CaseResult& c : report.cases) {
            if (stage_of(c) != stage) continue;
            t.add(c.verdict, c.seconds);
            all.add(c.verdict, c.seconds);
            testcases += testcase(c, fmt::format("{}.{}", plugin, stage));
        }
        if (t.tests > 0) suites += suite(report, stage, t, testcases);  // no empty stages
    }
    const bool whole_run = std::isfinite(report.seconds) && report.seconds > 0;
    return fmt::format(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<testsuites name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"{}\"{}>\n{}</testsuites>\n",
        attr(plugin), all.tests, all.failures, all.errors,
        seconds_attribute(whole_run ? report.seconds : all.seconds), suites);
}

Result<void> write_junit_report(const ValidationReport& report, const std::filesystem::path& file) {
    return write_file_atomically(file, junit_xml(report));
}

}  // namespace acetate::harness
