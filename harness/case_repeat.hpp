#pragma once
// `validate --repeat N --shuffle`: every case runs N times, each run in a fresh process, all the
// runs in one random order; a case whose verdict is not the same in every run is FLAKY, a
// failing verdict. What one run in a fixed order hides shows up here: a result that depends on
// what ran before it, on timing, on a file a previous process left behind, on the address space.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "case_batch.hpp"

namespace acetate::harness {

// The pseudo-check a FLAKY case carries, naming each run's verdict.
inline constexpr const char* kRepeatCheck = "repeat";

struct Repetition {
    unsigned runs = 1;                     // --repeat
    std::optional<uint64_t> shuffle_seed;  // --shuffle: the order's seed (printed: reusable)
};

// Runs every case `runs` times (run r >= 2 in the folder cases/<case>-run<r>), in the order the
// shuffle seed draws when there is one, and returns one result per case, in the order of
// `cases` (merge_runs).
std::vector<CaseResult> run_repeated(CaseBatch& batch, const std::vector<CaseSpec>& cases,
                                     const Repetition& repetition);

// One case's runs, in run order, merged: the first run's result when every verdict is the same;
// otherwise the worst run's result, its verdict FLAKY, with a `repeat` check listing the
// verdicts run by run.
CaseResult merge_runs(std::vector<CaseResult> runs);

}  // namespace acetate::harness
