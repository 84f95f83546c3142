#pragma once
// junit.xml for `acetate-harness validate`: GitLab, Jenkins and GitHub show JUnit XML natively
// (test tabs, merge-request widgets, annotations), so a CI job publishes a validation run
// without reading report.json. The document validates against the Jenkins xUnit plugin's
// junit-10.xsd (tests/data/junit.xsd).
//
// Layout: <testsuites name="<plugin id>"> with one <testsuite> per validation stage
// (ALPHA_TESTED, INTEGRATED) and one <testcase> per case. FAIL is a <failure>, CRASH and
// TIMEOUT an <error>, SKIP <skipped/>; WARN passes with its warnings in <system-out>; a
// case's log (the child's stderr) is its <system-err>. A run that could not start is one
// suite holding one errored testcase.

#include <filesystem>
#include <string>

#include "core/result.hpp"
#include "report.hpp"

namespace acetate::harness {

// The whole document, UTF-8, ending with a newline. Any text is safe in it: XML's special
// characters are escaped, and what XML 1.0 cannot hold (control characters, invalid UTF-8) is
// replaced.
std::string junit_xml(const ValidationReport& report);

// junit_xml() written atomically, as report.json is (core/atomic_file.hpp): on failure `file`
// is untouched, nothing is left behind, and the error is one line naming `file`.
Result<void> write_junit_report(const ValidationReport& report, const std::filesystem::path& file);

}  // namespace acetate::harness
