#pragma once
// Every check a case can report, registered once: its name, the contract rule it enforces,
// which cases run it, whether a waiver may name it, and what fails it. The waivers, the table
// of checks in docs/harness.md and the one in docs/contract.md are made from this list
// (tests/unit/check_registry_test.cpp keeps the documents equal to it; the battery test fails
// on a reported check that is not here). Adding a check: docs/harness.md, "Adding a check".

#include <span>
#include <string>
#include <string_view>

namespace acetate::harness {

struct CheckInfo {
    std::string_view name;    // as reports, waivers and the docs write it
    std::string_view rule;    // the contract rule, "2a, 2b"; or "none: <why it exists>"
    std::string_view cases;   // which cases run it (Markdown)
    bool waivable = true;     // a waiver may turn its FAIL into WAIVED
    bool in_contract = true;  // listed in docs/contract.md's table (not the run's own rows)
    std::string_view fails;   // what fails it, one sentence (Markdown)
};

std::span<const CheckInfo> registered_checks();
// The registered check of that name; null when there is none.
const CheckInfo* find_registered_check(std::string_view name);

// The tables the documents hold between their "checks" markers (check_registry_test.cpp):
// docs/harness.md's "| check | rule | in which cases | waivable |" and docs/contract.md's
// "| check | rule | what fails it |".
std::string harness_checks_table();
std::string contract_checks_table();

}  // namespace acetate::harness
