#include "case_repeat.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <utility>

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
    // Each run's result lands in its case's slot as it finishes; a case whose runs are all in
    // is merged and handed on at once (the batch's on_result sees cases, not runs).
    std::vector<std::vector<CaseResult>> by_case(cases.size(), std::vector<CaseResult>(runs));
    std::vector<unsigned> finished(cases.size(), 0);
    auto on_case = std::exchange(batch.on_result, {});
    // Repeated, each run has a process of its own: a verdict that changes is the plugin's, not
    // that of the cases before it in a shared process.
    const unsigned per_process =
        std::exchange(batch.cases_per_process, runs > 1 ? 1u : batch.cases_per_process);
    batch.on_result = [&](size_t j, const CaseResult& result) {
        const Slot& slot = order[j];
        by_case[slot.case_index][slot.run] = result;
        if (++finished[slot.case_index] == runs && on_case)
            on_case(slot.case_index, merge_runs(by_case[slot.case_index]));
    };
    run_case_batch(batch, specs, folders);
    batch.on_result = std::move(on_case);
    batch.cases_per_process = per_process;
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
