#include "case_repeat.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <random>

namespace acetate::harness {

std::vector<CaseResult> run_repeated(CaseBatch& batch, const std::vector<CaseSpec>& cases,
                                     const Repetition& repetition) {
    const unsigned runs = std::max(1u, repetition.runs);
    struct Slot {
        size_t case_index;
        unsigned run;
    };
    std::vector<Slot> order;
    for (unsigned run = 0; run < runs; ++run)
        for (size_t i = 0; i < cases.size(); ++i) order.push_back({i, run});
    if (repetition.shuffle_seed) {
        std::mt19937_64 random(*repetition.shuffle_seed);
        std::shuffle(order.begin(), order.end(), random);
    }
    std::vector<CaseSpec> specs;
    std::vector<std::string> folders;
    for (const Slot& slot : order) {
        const CaseSpec& spec = cases[slot.case_index];
        specs.push_back(spec);
        // Run 1 keeps the plain folder, so the report's pictures are where a single run puts them.
        folders.push_back(case_folder(spec.id) +
                          (slot.run == 0 ? "" : fmt::format("-run{}", slot.run + 1)));
    }
    std::vector<CaseResult> results = run_case_batch(batch, specs, folders);

    std::vector<std::vector<CaseResult>> by_case(cases.size(), std::vector<CaseResult>(runs));
    for (size_t j = 0; j < order.size(); ++j)
        by_case[order[j].case_index][order[j].run] = std::move(results[j]);
    std::vector<CaseResult> merged;
    for (std::vector<CaseResult>& case_runs : by_case)
        merged.push_back(merge_runs(std::move(case_runs)));
    return merged;
}

CaseResult merge_runs(std::vector<CaseResult> runs) {
    if (runs.empty()) return {};
    const bool same = std::all_of(runs.begin(), runs.end(), [&](const CaseResult& r) {
        return r.verdict == runs.front().verdict;
    });
    if (same) return std::move(runs.front());

    size_t worst = 0;
    std::vector<std::string> verdicts;
    for (size_t i = 0; i < runs.size(); ++i) {
        verdicts.push_back(to_string(runs[i].verdict));
        if (int(runs[i].verdict) > int(runs[worst].verdict)) worst = i;
    }
    CaseResult result = std::move(runs[worst]);
    const std::string what = fmt::format(
        "the verdict changed across {} runs, each in a fresh process: {} (run {} shown)",
        runs.size(), fmt::join(verdicts, ", "), worst + 1);
    result.message = result.message.empty() ? what : what + "; " + result.message;
    result.verdict = Verdict::Flaky;
    CheckResult repeat;
    repeat.check = kRepeatCheck;
    repeat.verdict = Verdict::Flaky;
    repeat.message = what;
    result.checks.push_back(std::move(repeat));
    return result;
}

}  // namespace acetate::harness
