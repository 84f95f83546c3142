// junit.xml (harness/report_junit.hpp): suites per validation stage and their counts, how each
// verdict is written, the first example pixel and the reproduce line in a failure, escaping of
// hostile plugin text, and the document valid against the Jenkins JUnit schema
// (tests/data/junit.xsd) by xmllint, which must be installed: its absence fails the test. Also
// the atomic write's one-line errors. No GPU needed.

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "report_fixtures.hpp"
#include "report_junit.hpp"
#include "test_files.hpp"

namespace acetate::harness {
namespace {

using ::acetate::test::read_file;
using ::acetate::test::scratch_dir;

namespace fs = std::filesystem;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
const std::string kHostile = "rgb > a <&\"' \x01 end";

std::set<std::string> names_in(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
    return names;
}

using report_test::check;

// A case as report_fixtures.hpp builds it, with a time and a reproduce line (JUnit shows both).
CaseResult case_with(std::string id, Verdict verdict, std::vector<CheckResult> checks = {},
                     std::string message = "") {
    CaseResult c =
        report_test::case_with(std::move(id), verdict, std::move(checks), std::move(message));
    c.seconds = 0.25;
    c.reproduce = fmt::format("acetate-harness validate bloom.so --case {} --seed 42", c.id);
    return c;
}

// Every verdict once, six cases for ALPHA_TESTED and one for INTEGRATED.
ValidationReport sample_report() {
    ValidationReport r;
    r.harness_version = "1.1.0";
    r.plugin_file = "build/plugins/bloom.so";
    r.id = "acetate.bloom";
    r.version = "1.2.0";
    r.binary_sha256 = "ab12cd34";
    r.source_digest = "ef56";
    r.strictness = 7;
    r.seed = 42;
    r.started_at = "2025-11-22T08:51:00Z";
    r.seconds = 12.5;

    CaseResult failing =
        case_with("params/max", Verdict::Fail,
                  {check("coverage", Verdict::Pass, "outside the coverage: unchanged"),
                   check("premultiplied", Verdict::Fail, kHostile)});
    Violation first;
    first.x = 36;
    first.y = 22;
    first.floor = 2;
    first.input = {0.25f, 0.5f, 0.125f, 1.0f};
    first.output = {kNaN, 0.5f, kInf, 1.0f};
    first.what = "rgb is not finite";
    Violation second = first;
    second.x = 99;
    second.what = "the second example";
    failing.checks[1].violations = 17;
    failing.checks[1].examples = {first, second};
    failing.log = "child: \x1b[31mred\x1b[0m and a byte that is not UTF-8: \xff";

    CaseResult crashed = case_with("sizes/4096x4096", Verdict::Crash, {}, "killed by SIGSEGV");
    crashed.seconds = std::numeric_limits<double>::quiet_NaN();  // no time: no attribute
    r.cases = {case_with("sizes/1x1", Verdict::Pass,
                         {check("premultiplied", Verdict::Pass, "all pixels premultiplied")}),
               failing,
               crashed,
               case_with("params/random-3", Verdict::Timeout, {}, "ran past the 60 s limit"),
               case_with("lights/none", Verdict::Skip, {}, "the plugin reads no lights"),
               case_with("sizes/odd", Verdict::Warn,
                         {check("coverage", Verdict::Warn, "3 pixels differ by 1 ulp")}),
               case_with("integration/stack", Verdict::Pass)};
    return r;
}

// The text from `start` to the end of the element it opens (its closing tag, or "/>").
std::string element(const std::string& xml, const std::string& start, const std::string& tag) {
    const size_t at = xml.find(start);
    if (at == std::string::npos) return "";
    const size_t open_end = xml.find('>', at);
    if (xml[open_end - 1] == '/') return xml.substr(at, open_end + 1 - at);
    const std::string close = "</" + tag + ">";
    return xml.substr(at, xml.find(close, at) + close.size() - at);
}

std::string testcase(const std::string& xml, const std::string& id) {
    return element(xml, fmt::format("<testcase name=\"{}\"", id), "testcase");
}

// Runs `xmllint --noout --schema tests/data/junit.xsd file`: its exit status and output.
std::pair<int, std::string> xmllint(const fs::path& file) {
    const std::string command =
        fmt::format("xmllint --noout --schema '{}' '{}' 2>&1", ACETATE_JUNIT_XSD, file.string());
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return {-1, "popen failed"};
    std::string output;
    char buffer[4096];
    while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
    const int status = ::pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

void expect_schema_valid(const fs::path& file) {
    ASSERT_EQ(std::system("command -v xmllint >/dev/null 2>&1"), 0)
        << "xmllint is not installed: the JUnit schema test needs it "
           "(apt-get install libxml2-utils, or scripts/install-packages.sh)";
    ASSERT_TRUE(fs::exists(ACETATE_JUNIT_XSD)) << ACETATE_JUNIT_XSD;
    const auto [status, output] = xmllint(file);
    EXPECT_EQ(status, 0) << output << "\n" << read_file(file);
}

TEST(Junit, SuitesPerStageWithTheirCounts) {
    const std::string xml = junit_xml(sample_report());
    EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", 0), 0u);
    EXPECT_NE(xml.find("<testsuites name=\"acetate.bloom\" tests=\"7\" failures=\"1\" "
                       "errors=\"2\" time=\"12.500\">"),
              std::string::npos)
        << xml;
    EXPECT_NE(xml.find("<testsuite name=\"acetate.bloom ALPHA_TESTED\" tests=\"6\" failures=\"1\" "
                       "errors=\"2\" skipped=\"1\" time=\"1.250\" "
                       "timestamp=\"2025-11-22T08:51:00Z\">"),
              std::string::npos)
        << xml;
    EXPECT_NE(xml.find("<testsuite name=\"acetate.bloom INTEGRATED\" tests=\"1\" failures=\"0\" "
                       "errors=\"0\" skipped=\"0\" time=\"0.250\" "
                       "timestamp=\"2025-11-22T08:51:00Z\">"),
              std::string::npos)
        << xml;
}

TEST(Junit, CasesGroupedByStage) {
    const std::string xml = junit_xml(sample_report());
    const std::string alpha =
        element(xml, "<testsuite name=\"acetate.bloom ALPHA_TESTED\"", "testsuite");
    const std::string integrated =
        element(xml, "<testsuite name=\"acetate.bloom INTEGRATED\"", "testsuite");
    for (const char* id : {"sizes/1x1", "params/max", "sizes/4096x4096", "params/random-3",
                           "lights/none", "sizes/odd"}) {
        EXPECT_NE(
            alpha.find(fmt::format("name=\"{}\" classname=\"acetate.bloom.ALPHA_TESTED\"", id)),
            std::string::npos)
            << id;
        EXPECT_EQ(integrated.find(fmt::format("name=\"{}\"", id)), std::string::npos) << id;
    }
    EXPECT_NE(integrated.find("<testcase name=\"integration/stack\" "
                              "classname=\"acetate.bloom.INTEGRATED\" time=\"0.250\"/>"),
              std::string::npos)
        << integrated;
    EXPECT_EQ(alpha.find("integration/"), std::string::npos);
    // Each suite says which plugin and run it is.
    for (const std::string& suite : {alpha, integrated}) {
        EXPECT_NE(suite.find("<property name=\"plugin_id\" value=\"acetate.bloom\"/>"),
                  std::string::npos);
        EXPECT_NE(suite.find("<property name=\"plugin_version\" value=\"1.2.0\"/>"),
                  std::string::npos);
        EXPECT_NE(suite.find("<property name=\"binary_sha256\" value=\"ab12cd34\"/>"),
                  std::string::npos);
        EXPECT_NE(suite.find("<property name=\"source_digest\" value=\"ef56\"/>"),
                  std::string::npos);
        EXPECT_NE(suite.find("<property name=\"strictness\" value=\"7\"/>"), std::string::npos);
        EXPECT_NE(suite.find("<property name=\"seed\" value=\"42\"/>"), std::string::npos);
        EXPECT_NE(suite.find("<property name=\"harness_version\" value=\"1.1.0\"/>"),
                  std::string::npos);
    }
}

TEST(Junit, FailureCarriesTheFirstExamplePixelAndTheReproduceLine) {
    const std::string failing = testcase(junit_xml(sample_report()), "params/max");
    ASSERT_NE(failing.find("<failure message=\"premultiplied: rgb &gt; a"), std::string::npos)
        << failing;
    EXPECT_NE(failing.find("type=\"FAIL\""), std::string::npos);
    const std::string pixel =
        "17 violations, the first at (36, 22) on floor 2: input rgba (0.25, 0.5, 0.125, 1) -&gt; "
        "output rgba (NaN, 0.5, Infinity, 1): rgb is not finite";
    // In the one-line message attribute and in the body.
    EXPECT_NE(failing.find("; " + pixel + "\" type=\"FAIL\">"), std::string::npos) << failing;
    EXPECT_NE(failing.find("\n  " + pixel + "\n"), std::string::npos) << failing;
    EXPECT_EQ(failing.find("the second example"), std::string::npos);  // only the first
    EXPECT_EQ(failing.find("coverage"), std::string::npos);            // only failing checks
    EXPECT_NE(
        failing.find(
            "reproduce: acetate-harness validate bloom.so --case params/max --seed 42\n</failure>"),
        std::string::npos)
        << failing;
    EXPECT_NE(failing.find("<system-err>child: "), std::string::npos) << failing;
}

TEST(Junit, EachVerdictAsJunitSaysIt) {
    const std::string xml = junit_xml(sample_report());
    EXPECT_EQ(testcase(xml, "sizes/1x1"),
              "<testcase name=\"sizes/1x1\" classname=\"acetate.bloom.ALPHA_TESTED\" "
              "time=\"0.250\"/>");

    const std::string crashed = testcase(xml, "sizes/4096x4096");
    EXPECT_NE(crashed.find("<error message=\"killed by SIGSEGV\" type=\"CRASH\">"),
              std::string::npos)
        << crashed;
    EXPECT_NE(crashed.find("reproduce: acetate-harness validate bloom.so --case sizes/4096x4096"),
              std::string::npos);
    EXPECT_EQ(crashed.find("time="), std::string::npos) << "a NaN time has no attribute";

    const std::string timed_out = testcase(xml, "params/random-3");
    EXPECT_NE(timed_out.find("<error message=\"ran past the 60 s limit\" type=\"TIMEOUT\">"),
              std::string::npos)
        << timed_out;

    const std::string skipped = testcase(xml, "lights/none");
    EXPECT_NE(skipped.find("<skipped message=\"the plugin reads no lights\"/>"), std::string::npos)
        << skipped;

    const std::string warned = testcase(xml, "sizes/odd");
    EXPECT_NE(warned.find("<system-out>warning: coverage: 3 pixels differ by 1 ulp\n"
                          "</system-out>"),
              std::string::npos)
        << warned;
    for (const char* verdict_element : {"<failure", "<error", "<skipped"})
        EXPECT_EQ(warned.find(verdict_element), std::string::npos) << verdict_element;
}

TEST(Junit, HostileTextIsEscapedAndForbiddenCharactersReplaced) {
    const std::string failing = testcase(junit_xml(sample_report()), "params/max");
    const std::string escaped = "rgb &gt; a &lt;&amp;&quot;&apos; #x01 end";
    EXPECT_NE(failing.find("message=\"premultiplied: " + escaped), std::string::npos) << failing;
    EXPECT_NE(failing.find("premultiplied: " + escaped + "\n"), std::string::npos) << failing;
    // The log: colour codes written as "#x1B", the stray byte as U+FFFD.
    EXPECT_NE(failing.find("<system-err>child: #x1B[31mred#x1B[0m and a byte that is not "
                           "UTF-8: \xEF\xBF\xBD</system-err>"),
              std::string::npos)
        << failing;

    const std::string xml = junit_xml(sample_report());
    for (char c = 0; c < 0x20; ++c) {
        if (c == '\n') continue;
        EXPECT_EQ(xml.find(c), std::string::npos) << "control character " << int(c);
    }
    EXPECT_EQ(xml.find('\xff'), std::string::npos);
}

TEST(Junit, WrittenFileIsValidAgainstTheJunitSchema) {
    const fs::path dir = scratch_dir();
    ValidationReport report = sample_report();
    // Text in every attribute and body that could break the document.
    report.id = "acetate.<bloom>&\"'";
    report.started_at = "\t2025\r\n";
    report.cases[1].description = "a\x02\x7f\xc3\x28 \xed\xa0\x80 \xef\xbf\xbe \xf4\x90\x80\x80";
    report.cases[0].seconds = -1;
    report.seconds = std::numeric_limits<double>::infinity();
    ASSERT_TRUE(write_junit_report(report, dir / "junit.xml").ok());
    expect_schema_valid(dir / "junit.xml");
    EXPECT_EQ(read_file(dir / "junit.xml"), junit_xml(report));
    EXPECT_EQ(names_in(dir), std::set<std::string>{"junit.xml"});  // no temporary left behind
}

TEST(Junit, RunThatCouldNotStartIsOneErroredTestcase) {
    const fs::path dir = scratch_dir();
    ValidationReport report;
    report.harness_version = "1.1.0";
    report.plugin_file = "build/plugins/missing.so";
    report.started_at = "2025-11-22T08:51:00Z";
    report.error = "build/plugins/missing.so: cannot open <it>: No such file";
    const std::string xml = junit_xml(report);
    EXPECT_NE(xml.find("<testsuites name=\"build/plugins/missing.so\" tests=\"1\" failures=\"0\" "
                       "errors=\"1\""),
              std::string::npos)
        << xml;
    EXPECT_NE(xml.find("<testsuite name=\"build/plugins/missing.so validate\" tests=\"1\" "
                       "failures=\"0\" errors=\"1\" skipped=\"0\""),
              std::string::npos)
        << xml;
    EXPECT_NE(xml.find("<error message=\"build/plugins/missing.so: cannot open &lt;it&gt;: No "
                       "such file\" type=\"ERROR\">the validation run could not start or complete"),
              std::string::npos)
        << xml;
    EXPECT_EQ(xml.find("<testsuite ", xml.find("<testsuite ") + 1), std::string::npos)
        << "one suite only";
    ASSERT_TRUE(write_junit_report(report, dir / "junit.xml").ok());
    expect_schema_valid(dir / "junit.xml");
}

TEST(Junit, RunWithoutCasesIsStillAValidDocument) {
    const fs::path dir = scratch_dir();
    ValidationReport report;
    report.id = "acetate.bloom";
    ASSERT_TRUE(write_junit_report(report, dir / "junit.xml").ok());
    EXPECT_NE(read_file(dir / "junit.xml").find("tests=\"0\""), std::string::npos);
    expect_schema_valid(dir / "junit.xml");
}

TEST(Junit, MissingFolderIsAOneLineErrorNamingTheFile) {
    const fs::path dir = scratch_dir();
    const fs::path target = dir / "no-such-folder" / "junit.xml";
    const Result<void> written = write_junit_report(sample_report(), target);
    ASSERT_FALSE(written.ok());
    const std::string& message = written.error().message;
    EXPECT_EQ(message.rfind(target.string() + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir / "no-such-folder"));
}

TEST(Junit, UnwritableTargetLeavesNoPartialFile) {
    const fs::path dir = scratch_dir();
    // A folder where the file should go: refused, nothing written beside it.
    fs::create_directory(dir / "junit.xml");
    const Result<void> refused = write_junit_report(sample_report(), dir / "junit.xml");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find((dir / "junit.xml").string()), std::string::npos);
    EXPECT_EQ(refused.error().message.find('\n'), std::string::npos) << refused.error().message;
    EXPECT_TRUE(fs::is_empty(dir / "junit.xml"));
    EXPECT_EQ(names_in(dir), std::set<std::string>{"junit.xml"});

    // A write that fails half-way (the file-size limit, which holds for root too, in a child so
    // the limit stays there): the old report is intact and no temporary is left.
    fs::remove(dir / "junit.xml");
    std::ofstream(dir / "junit.xml") << "the previous report\n";
    ValidationReport big = sample_report();
    big.cases[1].log = std::string(256 * 1024, 'x');
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        ::signal(SIGXFSZ, SIG_IGN);  // the write fails with EFBIG instead of killing the child
        const rlimit limit{4096, 4096};
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(2);
        const Result<void> written = write_junit_report(big, dir / "junit.xml");
        const bool one_line = !written.ok() &&
                              written.error().message.find((dir / "junit.xml").string()) == 0 &&
                              written.error().message.find('\n') == std::string::npos;
        ::_exit(written.ok() ? 0 : one_line ? 1 : 3);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 1) << "0: written despite the limit, 2: setrlimit failed, "
                                         "3: the error was not one line naming the file";
    EXPECT_EQ(read_file(dir / "junit.xml"), "the previous report\n");
    EXPECT_EQ(names_in(dir), std::set<std::string>{"junit.xml"});
}

}  // namespace
}  // namespace acetate::harness
