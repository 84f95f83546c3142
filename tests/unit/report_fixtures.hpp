#pragma once
// What the harness report tests share: a check and a case built in one line each.

#include <string>
#include <utility>
#include <vector>

#include "report.hpp"

namespace acetate::harness::report_test {

inline CheckResult check(std::string name, Verdict verdict, std::string message = "") {
    CheckResult c;
    c.check = std::move(name);
    c.verdict = verdict;
    c.message = std::move(message);
    return c;
}

inline CaseResult case_with(std::string id, Verdict verdict, std::vector<CheckResult> checks = {},
                            std::string message = "") {
    CaseResult c;
    c.id = std::move(id);
    c.verdict = verdict;
    c.checks = std::move(checks);
    c.message = std::move(message);
    return c;
}

}  // namespace acetate::harness::report_test
