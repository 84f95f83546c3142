// The harness's reports (harness/report.hpp): verdict names, a child's result file read back
// exactly (NaN and infinities included) and its errors naming the field, the per-check summary
// with its "process" pseudo-check, when a run fails, and the HTML page: escaped, anchored,
// failing cases first, images referenced. No GPU needed.

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "report.hpp"
#include "report_fixtures.hpp"
#include "test_files.hpp"

namespace acetate::harness {
namespace {

using ::acetate::test::read_file;
using ::acetate::test::scratch_dir;

namespace fs = std::filesystem;
using nlohmann::json;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

using report_test::case_with;
using report_test::check;

// A case that exercises every field, with the values JSON cannot hold as numbers.
CaseResult full_case() {
    Violation nan_in_rgb;
    nan_in_rgb.x = 36;
    nan_in_rgb.y = 22;
    nan_in_rgb.floor = 2;
    nan_in_rgb.input = {0.25f, 0.5f, 0.1f, 1.0f};
    nan_in_rgb.output = {kNaN, kInf, -kInf, -0.0f};
    nan_in_rgb.what = "rgb is not finite";

    Violation extremes;
    extremes.x = 0;
    extremes.y = 0;
    extremes.floor = -1;
    extremes.input = {std::numeric_limits<float>::max(), std::numeric_limits<float>::denorm_min(),
                      std::numeric_limits<float>::lowest(), 1.0f / 3.0f};
    extremes.output = {0.2f, 0.7f, 1e-30f, 0.999999f};
    extremes.what = "a = 0.999999 but rgb > a";

    CheckResult premultiplied = check("premultiplied", Verdict::Fail, "rgb <= a + 1e-6");
    premultiplied.violations = 1234;
    premultiplied.examples = {nan_in_rgb, extremes};
    premultiplied.images = {{"heatmap.floor2", "cases/sizes-37x23/premultiplied.floor2.png"}};

    CaseResult c = case_with("sizes/37x23", Verdict::Fail,
                             {premultiplied, check("coverage", Verdict::Pass, "stencil kept")});
    c.description = "a 37x23 canvas with odd sizes";
    c.seed = std::numeric_limits<uint64_t>::max();
    c.images = {{"input.floor2", "cases/sizes-37x23/input.floor2.png"},
                {"output.floor2", "cases/sizes-37x23/output.floor2.png"}};
    c.seconds = 1.625;
    c.reproduce = "acetate-harness validate plugin.so --case sizes/37x23 --seed 42";
    c.log = "line one\nline two \"quoted\"\n";
    c.output_digest = std::string(64, 'a');
    return c;
}

// Float equality that holds NaN equal to NaN and tells 0 from -0: "the same bits" for the
// values the report writes.
void expect_same(const std::array<float, 4>& a, const std::array<float, 4>& b,
                 const std::string& where) {
    for (size_t i = 0; i < 4; ++i) {
        if (std::isnan(a[i])) {
            EXPECT_TRUE(std::isnan(b[i])) << where << "[" << i << "]";
        } else {
            EXPECT_EQ(std::bit_cast<uint32_t>(a[i]), std::bit_cast<uint32_t>(b[i]))
                << where << "[" << i << "]: " << a[i] << " vs " << b[i];
        }
    }
}

void expect_same(const CaseResult& a, const CaseResult& b) {
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.description, b.description);
    EXPECT_EQ(a.seed, b.seed);
    EXPECT_EQ(a.verdict, b.verdict);
    EXPECT_EQ(a.message, b.message);
    EXPECT_EQ(a.images, b.images);
    EXPECT_EQ(a.seconds, b.seconds);
    EXPECT_EQ(a.reproduce, b.reproduce);
    EXPECT_EQ(a.log, b.log);
    EXPECT_EQ(a.output_digest, b.output_digest);
    ASSERT_EQ(a.checks.size(), b.checks.size());
    for (size_t i = 0; i < a.checks.size(); ++i) {
        const CheckResult &x = a.checks[i], &y = b.checks[i];
        EXPECT_EQ(x.check, y.check);
        EXPECT_EQ(x.verdict, y.verdict);
        EXPECT_EQ(x.message, y.message);
        EXPECT_EQ(x.violations, y.violations);
        EXPECT_EQ(x.images, y.images);
        ASSERT_EQ(x.examples.size(), y.examples.size());
        for (size_t k = 0; k < x.examples.size(); ++k) {
            const Violation &v = x.examples[k], &w = y.examples[k];
            EXPECT_EQ(v.x, w.x);
            EXPECT_EQ(v.y, w.y);
            EXPECT_EQ(v.floor, w.floor);
            EXPECT_EQ(v.what, w.what);
            expect_same(v.input, w.input, fmt::format("checks[{}].examples[{}].input", i, k));
            expect_same(v.output, w.output, fmt::format("checks[{}].examples[{}].output", i, k));
        }
    }
}

// The error message of a result file that must be refused.
std::string refusal(const json& document) {
    Result<CaseResult> result = case_result_from_json(document, "child.json");
    if (result.ok()) return "(accepted)";
    EXPECT_EQ(result.error().code, ErrorCode::InvalidInput);
    return result.error().message;
}

// ---- verdicts -------------------------------------------------------------------------------

TEST(Verdicts, NamesRoundTripAndLowerCaseIsAccepted) {
    const std::vector<std::pair<Verdict, std::string>> names = {
        {Verdict::Pass, "PASS"}, {Verdict::Skip, "SKIP"},       {Verdict::Warn, "WARN"},
        {Verdict::Fail, "FAIL"}, {Verdict::Timeout, "TIMEOUT"}, {Verdict::Crash, "CRASH"}};
    for (const auto& [verdict, name] : names) {
        EXPECT_EQ(to_string(verdict), name);
        EXPECT_EQ(parse_verdict(name), verdict) << name;
        std::string lower = name;
        for (char& c : lower) c = char(std::tolower(c));
        EXPECT_EQ(parse_verdict(lower), verdict) << lower;
    }
    EXPECT_EQ(parse_verdict("MAYBE"), std::nullopt);
    EXPECT_EQ(parse_verdict(""), std::nullopt);
    EXPECT_EQ(parse_verdict("PASSED"), std::nullopt);
}

TEST(Verdicts, FailTimeoutAndCrashFail) {
    EXPECT_FALSE(is_failing(Verdict::Pass));
    EXPECT_FALSE(is_failing(Verdict::Skip));
    EXPECT_FALSE(is_failing(Verdict::Warn));
    EXPECT_TRUE(is_failing(Verdict::Fail));
    EXPECT_TRUE(is_failing(Verdict::Timeout));
    EXPECT_TRUE(is_failing(Verdict::Crash));
}

// ---- JSON -----------------------------------------------------------------------------------

TEST(CaseResultJson, RoundTripsExactlyThroughText) {
    const CaseResult original = full_case();
    // Through text, as the parent reads the file the child wrote.
    const std::string text = to_json(original).dump(2);
    Result<CaseResult> back = case_result_from_json(json::parse(text), "child.json");
    ASSERT_TRUE(back.ok()) << back.error().message;
    expect_same(original, back.value());
    // And the re-encoded result is the same document.
    EXPECT_EQ(to_json(back.value()).dump(), to_json(original).dump());
}

TEST(CaseResultJson, NonFiniteFloatsAreStringsNotNull) {
    const json j = to_json(full_case());
    const json& output = j["checks"][0]["examples"][0]["output"];
    EXPECT_EQ(output[0], "NaN");
    EXPECT_EQ(output[1], "Infinity");
    EXPECT_EQ(output[2], "-Infinity");
    EXPECT_TRUE(output[3].is_number());
    EXPECT_EQ(j.dump().find("null"), std::string::npos) << j.dump();

    CaseResult infinite_time = case_with("slow", Verdict::Timeout);
    infinite_time.seconds = std::numeric_limits<double>::infinity();
    EXPECT_EQ(to_json(infinite_time)["seconds"], "Infinity");
}

TEST(CaseResultJson, FieldsAreSnakeCaseAndVerdictsNames) {
    const json j = to_json(full_case());
    for (const char* key : {"id", "description", "seed", "verdict", "message", "checks", "images",
                            "seconds", "reproduce", "log", "output_digest"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["verdict"], "FAIL");
    EXPECT_EQ(j["checks"][1]["verdict"], "PASS");
    EXPECT_EQ(j["images"]["input.floor2"], "cases/sizes-37x23/input.floor2.png");
    EXPECT_EQ(j["checks"][0]["images"]["heatmap.floor2"],
              "cases/sizes-37x23/premultiplied.floor2.png");
    EXPECT_EQ(j["checks"][0]["violations"], 1234);
    EXPECT_EQ(j["checks"][0]["examples"][1]["floor"], -1);
}

TEST(CaseResultJson, FloatsAreWrittenShort) {
    Violation v;
    v.input = {0.1f, 0.5f, 1.0f / 3.0f, 0.0f};
    const std::string text = to_json(v)["input"].dump();
    // The shortest decimals that read back as the same floats, not the doubles they widen to.
    EXPECT_EQ(text, "[0.1,0.5,0.33333334,0.0]");
}

// Shortest decimals go through double on the way back: check that this never lands on a
// neighbouring float, over random bit patterns (all exponents) and the edges.
TEST(CaseResultJson, FloatsRoundTripBitForBit) {
    std::mt19937 random(7);
    std::vector<uint32_t> bits = {0x00000001u, 0x007fffffu, 0x00800000u, 0x7f7fffffu,
                                  0x3f7fffffu, 0x3f800001u, 0x80000001u, 0xff7fffffu};
    for (int i = 0; i < 20000; ++i) bits.push_back(uint32_t(random()));
    for (uint32_t pattern : bits) {
        const float value = std::bit_cast<float>(pattern);
        if (!std::isfinite(value)) continue;  // the strings; covered above
        Violation v;
        v.x = v.y = 0;
        v.input = {value, value, value, value};
        CheckResult c = check("premultiplied", Verdict::Fail);
        c.examples = {v};
        CaseResult r = case_with("bits", Verdict::Fail, {c});
        Result<CaseResult> back =
            case_result_from_json(json::parse(to_json(r).dump()), "child.json");
        ASSERT_TRUE(back.ok()) << back.error().message;
        const float got = back->checks[0].examples[0].input[0];
        ASSERT_EQ(std::bit_cast<uint32_t>(got), pattern) << value << " came back as " << got;
    }
}

TEST(CaseResultJson, OptionalFieldsDefault) {
    Result<CaseResult> back = case_result_from_json(json{{"id", "sizes/1x1"}}, "child.json");
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(back->id, "sizes/1x1");
    EXPECT_EQ(back->verdict, Verdict::Pass);
    EXPECT_EQ(back->seed, 0u);
    EXPECT_TRUE(back->checks.empty());
    EXPECT_TRUE(back->images.empty());

    const json lower_case = {{"id", "a"}, {"verdict", "warn"}};
    EXPECT_EQ(case_result_from_json(lower_case, "child.json")->verdict, Verdict::Warn);
}

TEST(CaseResultJson, ErrorsNameTheFileAndTheField) {
    json missing_id = to_json(full_case());
    missing_id.erase("id");
    EXPECT_EQ(refusal(missing_id), "child.json: missing required field \"id\"");

    json bad_verdict = to_json(full_case());
    bad_verdict["checks"][1]["verdict"] = "MAYBE";
    EXPECT_EQ(
        refusal(bad_verdict).rfind(R"(child.json: checks[1].verdict: "MAYBE" is not a verdict)", 0),
        0u)
        << refusal(bad_verdict);

    json seed_text = to_json(full_case());
    seed_text["seed"] = "42";
    EXPECT_EQ(refusal(seed_text).rfind("child.json: seed: ", 0), 0u) << refusal(seed_text);

    json negative = to_json(full_case());
    negative["checks"][0]["violations"] = -1;
    EXPECT_EQ(refusal(negative).rfind("child.json: checks[0].violations: ", 0), 0u)
        << refusal(negative);

    json bad_channel = to_json(full_case());
    bad_channel["checks"][0]["examples"][1]["input"][2] = "nan";  // only "NaN" is ours
    EXPECT_EQ(refusal(bad_channel).rfind("child.json: checks[0].examples[1].input[2]: ", 0), 0u)
        << refusal(bad_channel);

    json huge_channel = to_json(full_case());
    huge_channel["checks"][0]["examples"][1]["output"][0] = 1e300;
    EXPECT_EQ(refusal(huge_channel).rfind("child.json: checks[0].examples[1].output[0]: ", 0), 0u)
        << refusal(huge_channel);

    json short_rgba = to_json(full_case());
    short_rgba["checks"][0]["examples"][0]["output"] = {1, 2, 3};
    EXPECT_EQ(refusal(short_rgba).rfind("child.json: checks[0].examples[0].output: ", 0), 0u)
        << refusal(short_rgba);

    json image_number = to_json(full_case());
    image_number["images"]["composite"] = 7;
    EXPECT_EQ(refusal(image_number).rfind("child.json: images.composite: must be a string", 0), 0u)
        << refusal(image_number);

    json misspelt = to_json(full_case());
    misspelt["checks"][0]["violation"] = 3;
    EXPECT_EQ(refusal(misspelt).rfind("child.json: checks[0]: unknown field \"violation\"", 0), 0u)
        << refusal(misspelt);

    json checks_object = to_json(full_case());
    checks_object["checks"] = json::object();
    EXPECT_EQ(refusal(checks_object).rfind("child.json: checks: must be an array", 0), 0u)
        << refusal(checks_object);

    EXPECT_EQ(refusal(json::array()).rfind("child.json: must be an object", 0), 0u)
        << refusal(json::array());
}

TEST(ReportJson, WritesEveryFieldAndEndsWithNewline) {
    const fs::path dir = scratch_dir();
    ValidationReport report;
    report.id = "org.example.tint";
    report.version = "1.0.0";
    report.strictness = 7;
    report.stages = {StageRun{"ALPHA_TESTED", true, false, "dry run"}};
    report.history = {HistoryLine{"2025-11-22T08:51:00Z", "review", "ana", "looked fine"}};
    report.cases = {full_case()};
    report.cases[0].log = "bad byte \xff here";  // a child's stderr is not always UTF-8

    ASSERT_TRUE(write_json_report(report, dir / "report.json").ok());
    const std::string text = read_file(dir / "report.json");
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text.back(), '\n');
    const json j = json::parse(text);
    EXPECT_EQ(j["id"], "org.example.tint");
    EXPECT_EQ(j["strictness"], 7);
    EXPECT_EQ(j["stages"][0]["stage"], "ALPHA_TESTED");
    EXPECT_EQ(j["stages"][0]["passed"], true);
    EXPECT_EQ(j["history"][0]["by"], "ana");
    EXPECT_EQ(j["cases"][0]["id"], "sizes/37x23");
    EXPECT_EQ(j["cases"][0]["checks"][0]["examples"][0]["output"][0], "NaN");
    EXPECT_EQ(j["error"], "");
}

TEST(ReportJson, UnwritableLocationIsAnErrorNamingThePath) {
    const fs::path dir = scratch_dir();
    std::ofstream(dir / "file.txt") << "a regular file, not a folder";
    const fs::path target = dir / "file.txt" / "sub" / "report.json";
    const Result<void> written = write_json_report(ValidationReport{}, target);
    ASSERT_FALSE(written.ok());
    EXPECT_NE(written.error().message.find(target.string()), std::string::npos)
        << written.error().message;
}

// ---- summaries ------------------------------------------------------------------------------

TEST(Summaries, WorstVerdictCountsAndFirstFailurePerCheck) {
    ValidationReport report;
    report.cases = {
        case_with("sizes/1x1", Verdict::Warn,
                  {check("premultiplied", Verdict::Pass, "ok"),
                   check("coverage", Verdict::Warn, "edge pixel touched")}),
        case_with("sizes/37x23", Verdict::Fail,
                  {check("coverage", Verdict::Fail, "wrote outside"),
                   check("premultiplied", Verdict::Pass, "ok"),
                   check("determinism", Verdict::Skip, "one run only")}),
        case_with("params/max", Verdict::Fail,
                  {check("premultiplied", Verdict::Warn, "close"),
                   check("coverage", Verdict::Fail, "again")}),
    };
    const std::vector<CheckSummary> s = summarize_checks(report);
    ASSERT_EQ(s.size(), 4u);
    // In order of first appearance, "process" last.
    EXPECT_EQ(s[0].check, "premultiplied");
    EXPECT_EQ(s[1].check, "coverage");
    EXPECT_EQ(s[2].check, "determinism");
    EXPECT_EQ(s[3].check, "process");

    EXPECT_EQ(s[0].verdict, Verdict::Warn);
    EXPECT_EQ(s[0].cases, (std::map<Verdict, uint64_t>{{Verdict::Pass, 2}, {Verdict::Warn, 1}}));
    EXPECT_EQ(s[0].first_failure, "params/max: close");  // no failure: the first warning

    EXPECT_EQ(s[1].verdict, Verdict::Fail);
    EXPECT_EQ(s[1].cases, (std::map<Verdict, uint64_t>{{Verdict::Warn, 1}, {Verdict::Fail, 2}}));
    // A failure wins over an earlier warning.
    EXPECT_EQ(s[1].first_failure, "sizes/37x23: wrote outside");

    EXPECT_EQ(s[2].verdict, Verdict::Skip);
    EXPECT_EQ(s[2].cases, (std::map<Verdict, uint64_t>{{Verdict::Skip, 1}}));
    EXPECT_EQ(s[2].first_failure, "");

    EXPECT_EQ(s[3].verdict, Verdict::Pass);
    EXPECT_EQ(s[3].cases, (std::map<Verdict, uint64_t>{{Verdict::Pass, 3}}));
    EXPECT_EQ(s[3].first_failure, "");
}

TEST(Summaries, ProcessCollectsCrashesAndTimeouts) {
    ValidationReport report;
    report.cases = {
        case_with("sizes/1x1", Verdict::Pass, {check("premultiplied", Verdict::Pass)}),
        case_with("params/max", Verdict::Timeout, {}, "no result after 60 s"),
        case_with("params/random-3", Verdict::Crash, {}, "SIGSEGV"),
        case_with("params/random-4", Verdict::Crash, {}, "SIGABRT"),
    };
    const std::vector<CheckSummary> s = summarize_checks(report);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].check, "premultiplied");
    EXPECT_EQ(s[0].verdict, Verdict::Pass);
    EXPECT_EQ(s[1].check, "process");
    EXPECT_EQ(s[1].verdict, Verdict::Crash);
    EXPECT_EQ(s[1].cases, (std::map<Verdict, uint64_t>{
                              {Verdict::Pass, 1}, {Verdict::Timeout, 1}, {Verdict::Crash, 2}}));
    EXPECT_EQ(s[1].first_failure, "params/max: no result after 60 s");
}

TEST(Summaries, NoCasesNoRows) {
    ValidationReport report;
    report.error = "the plugin did not load";
    EXPECT_TRUE(summarize_checks(report).empty());
    EXPECT_TRUE(count_verdicts(report).empty());
}

TEST(Summaries, CountVerdictsNamesOnlyThoseThatOccur) {
    ValidationReport report;
    report.cases = {case_with("a", Verdict::Pass), case_with("b", Verdict::Pass),
                    case_with("c", Verdict::Crash), case_with("d", Verdict::Warn)};
    EXPECT_EQ(count_verdicts(report),
              (std::map<std::string, uint64_t>{{"PASS", 2}, {"WARN", 1}, {"CRASH", 1}}));
}

TEST(Summaries, RunFailed) {
    ValidationReport report;
    report.cases = {case_with("a", Verdict::Pass, {check("premultiplied", Verdict::Pass)}),
                    case_with("b", Verdict::Warn, {check("coverage", Verdict::Warn)}),
                    case_with("c", Verdict::Skip)};
    EXPECT_FALSE(run_failed(report)) << "warnings and skips do not fail a run";

    ValidationReport failing_case = report;
    failing_case.cases[2].verdict = Verdict::Timeout;
    EXPECT_TRUE(run_failed(failing_case));

    // A failing check fails the run even if the case verdict forgot to say so.
    ValidationReport failing_check = report;
    failing_check.cases[0].checks.push_back(check("determinism", Verdict::Fail));
    EXPECT_TRUE(run_failed(failing_check));

    ValidationReport error = report;
    error.error = "the plugin did not load";
    EXPECT_TRUE(run_failed(error));
    EXPECT_FALSE(run_failed(ValidationReport{})) << "an empty run with no error";
}

// ---- HTML -----------------------------------------------------------------------------------

ValidationReport html_report() {
    ValidationReport report;
    report.harness_version = "0.1.0";
    report.plugin_file = "build/plugins/libtint.so";
    report.id = "org.example.tint";
    report.version = "1.0.0";
    report.display_name = "Tint & <Friends>";
    report.scope = "floor";
    report.coverage = "preserving";
    report.binary_sha256 = std::string(64, 'b');
    report.source_digest = std::string(64, 'c');
    report.stage_before = "REVIEWED";
    report.stage_after = "ALPHA_TESTED";
    report.seed = 42;
    report.started_at = "2025-11-22T08:51:00Z";
    report.seconds = 12.5;
    report.stages = {StageRun{"ALPHA_TESTED", false, false, "a case failed"}};
    report.history = {HistoryLine{"2025-11-20T10:00:00Z", "review", "ana <ana@example.org>", ""}};

    CaseResult passing =
        case_with("sizes/1x1", Verdict::Pass, {check("premultiplied", Verdict::Pass, "rgb <= a")});
    passing.images = {{"input.floor0", "cases/sizes-1x1/input.floor0.png"}};
    CaseResult failing = full_case();
    failing.checks[0].message = "<script>alert('x')</script>";
    CaseResult crashed = case_with("params/random-3", Verdict::Crash, {}, "SIGSEGV");
    crashed.log = "Segmentation fault \x1b[31m<core dumped>\x1b[0m";
    report.cases = {passing, failing, crashed};
    return report;
}

std::string render(const ValidationReport& report) {
    const fs::path dir = scratch_dir() / "report";  // not there yet: the writer makes it
    const Result<void> written = write_html_report(report, dir);
    EXPECT_TRUE(written.ok()) << written.error().message;
    return read_file(dir / "index.html");
}

size_t position(const std::string& html, const std::string& needle) {
    const size_t at = html.find(needle);
    EXPECT_NE(at, std::string::npos) << "missing: " << needle;
    return at;
}

TEST(HtmlReport, EscapesUntrustedText) {
    const std::string html = render(html_report());
    EXPECT_EQ(html.find("<script>alert"), std::string::npos);
    position(html, "&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;");
    position(html, "Tint &amp; &lt;Friends&gt;");
    position(html, "ana &lt;ana@example.org&gt;");
    position(html, "line two &quot;quoted&quot;");
    // The log's colour codes are dropped, its text kept.
    EXPECT_EQ(html.find('\x1b'), std::string::npos);
    position(html, "Segmentation fault [31m&lt;core dumped&gt;[0m");
}

TEST(HtmlReport, HeaderNamesThePluginAndTheRun) {
    const std::string html = render(html_report());
    for (const std::string& s :
         {std::string("org.example.tint"), std::string("1.0.0"),
          std::string("build/plugins/libtint.so"), std::string(64, 'b'), std::string(64, 'c'),
          std::string("REVIEWED → ALPHA_TESTED"), std::string("2025-11-22T08:51:00Z"),
          std::string("FAILED"), std::string("a case failed"), std::string("12.50 s")})
        position(html, s);
    EXPECT_EQ(html.find("class=\"error\""), std::string::npos) << "no error, no error box";

    ValidationReport error = html_report();
    error.error = "dlopen: <undefined symbol>";
    position(render(error), "<div class=\"error\">dlopen: &lt;undefined symbol&gt;</div>");
}

TEST(HtmlReport, ImagesAnchorsAndFailingCasesFirst) {
    const std::string html = render(html_report());
    // Images by their relative paths, pixelated over a checkerboard.
    position(html, "<img src=\"cases/sizes-1x1/input.floor0.png\"");
    position(html, "<img src=\"cases/sizes-37x23/premultiplied.floor2.png\"");
    position(html, "<figcaption>premultiplied: heatmap.floor2</figcaption>");
    position(html, "image-rendering: pixelated");
    position(html, "min-width: 96px");
    // Anchors from the ids; failing cases open and first, passing ones collapsed after them.
    const size_t failing = position(html, "<details class=\"case\" id=\"sizes-37x23\" open>");
    const size_t crashed = position(html, "<details class=\"case\" id=\"params-random-3\" open>");
    const size_t passing = position(html, "<details class=\"case\" id=\"sizes-1x1\">");
    EXPECT_LT(failing, crashed);
    EXPECT_LT(crashed, passing);
    // Summary rows link to the case that decided the check's verdict.
    position(html, "<a href=\"#sizes-37x23--premultiplied\">premultiplied</a>");
    position(html, "<tr id=\"sizes-37x23--premultiplied\">");
    position(html, "<a href=\"#params-random-3\">process</a>");
    position(html, "1 PASS · 1 FAIL");
    // The reproduce command and the examples.
    position(html,
             "<pre><code>acetate-harness validate plugin.so --case sizes/37x23 --seed 42"
             "</code></pre>");
    position(html, "premultiplied: 2 of 1234 offending pixels");
    position(html, "(NaN, Infinity, -Infinity, -0)");
}

TEST(HtmlReport, ImagePathsCannotEscapeTheAttribute) {
    ValidationReport report = html_report();
    report.cases[0].images = {{"x", "a b#c\".png"}, {"y", "javascript:alert(1)"}};
    const std::string html = render(report);
    position(html, "src=\"a%20b%23c%22.png\"");
    position(html, "src=\"javascript%3Aalert%281%29\"");
}

TEST(HtmlReport, ManyCasesCollapseThePassingOnesAndCapExamples) {
    ValidationReport report = html_report();
    for (int i = 0; i < 300; ++i)
        report.cases.push_back(case_with(fmt::format("params/random-{}", i + 10), Verdict::Pass,
                                         {check("premultiplied", Verdict::Pass)}));
    report.cases[1].checks[0].examples.assign(25, report.cases[1].checks[0].examples[1]);
    const std::string html = render(report);
    size_t open = 0, collapsed = 0;
    for (size_t at = html.find("<details class=\"case\""); at != std::string::npos;
         at = html.find("<details class=\"case\"", at + 1)) {
        const std::string tag = html.substr(at, html.find('>', at) - at);
        (tag.ends_with(" open") ? open : collapsed) += 1;
    }
    EXPECT_EQ(open, 2u);
    EXPECT_EQ(collapsed, 301u);
    position(html, "premultiplied: 10 of 1234 offending pixels");
    size_t rows = 0;
    for (size_t at = html.find("a = 0.999999 but rgb &gt; a"); at != std::string::npos;
         at = html.find("a = 0.999999 but rgb &gt; a", at + 1))
        ++rows;
    EXPECT_EQ(rows, 10u);
}

TEST(HtmlReport, DuplicateSlugsGetDistinctAnchors) {
    ValidationReport report;
    report.cases = {case_with("a/b", Verdict::Pass), case_with("a.b", Verdict::Pass),
                    case_with("summary", Verdict::Pass)};
    const std::string html = render(report);
    position(html, "id=\"a-b\"");
    position(html, "id=\"a-b-2\"");
    position(html, "id=\"summary-2\"");  // the page's own section keeps "summary"
}

TEST(HtmlReport, UnwritableLocationIsAnErrorNamingThePath) {
    const fs::path dir = scratch_dir();
    std::ofstream(dir / "file.txt") << "a regular file, not a folder";
    const fs::path target = dir / "file.txt" / "sub";
    const Result<void> written = write_html_report(html_report(), target);
    ASSERT_FALSE(written.ok());
    EXPECT_EQ(written.error().code, ErrorCode::Io);
    EXPECT_NE(written.error().message.find(target.string()), std::string::npos)
        << written.error().message;
}

}  // namespace
}  // namespace acetate::harness
