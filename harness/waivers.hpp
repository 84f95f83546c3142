#pragma once
// Waivers at validation time: a check a maintainer waived for this source (`acetate-harness
// waive`, Registry::waive) reads WAIVED instead of FAIL, with the waiver's reason beside it; an
// expired waiver fails the run until it is renewed or the plugin is fixed. docs/registry.md,
// "Waivers", says when a waiver is the right answer and when it is not.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "registry.hpp"
#include "report.hpp"

namespace acetate::harness {

// The checks a waiver may name: every check a case evaluates, and kStrictnessWaiver. Not the
// process check (a crash or a hang), `repeat` (a flaky plugin) or `load`: those are never
// accepted.
const std::vector<std::string>& waivable_checks();

// Today as YYYY-MM-DD, UTC.
std::string utc_today();

// In every case, a FAIL of a check with an unexpired waiver becomes WAIVED (its message
// prefixed with the waiver) and the case's verdict is recomputed; process failures (CRASH,
// TIMEOUT, FLAKY) stay. An expired waiver adds one failing case, "waivers/expired", naming it.
void apply_waivers(std::vector<CaseResult>& results, const std::vector<Waiver>& waivers,
                   std::string_view today);

// The waivers `registry` holds for this plugin's source (none when the file cannot be read: the
// run reports that separately).
std::vector<Waiver> waivers_of(const std::filesystem::path& registry, std::string_view id,
                               std::string_view version, std::string_view source_digest);

// One line per waiver, for `promote` and `status`: "reference until 2026-12-31 by NAME (reason)",
// with "EXPIRED" when it is.
std::vector<std::string> waiver_lines(const std::vector<Waiver>& waivers, std::string_view today);

}  // namespace acetate::harness
