// The checks and the case kinds are registered once (harness/checks.hpp, case_kinds.hpp): the
// tables of checks in docs/harness.md and docs/contract.md, and of case kinds in harness.md, are
// exactly what the registries make, between their markers, and the waivers accept exactly the
// waivable checks. A check added, renamed or reworded in the
// registry and not in the documents (or the other way round) fails here; the message holds
// the table to paste.

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "case_kinds.hpp"
#include "checks.hpp"
#include "test_files.hpp"
#include "waivers.hpp"

namespace acetate::harness {
namespace {

constexpr const char* kBegin =
    "<!-- checks: made from harness/checks.cpp; "
    "tests/unit/check_registry_test.cpp keeps it equal -->\n";
constexpr const char* kEnd = "<!-- end of checks -->";
constexpr const char* kKindsBegin =
    "<!-- case kinds: made from harness/case_kinds.cpp; "
    "tests/unit/check_registry_test.cpp keeps it equal -->\n";
constexpr const char* kKindsEnd = "<!-- end of case kinds -->";

// The text between the markers; "(no markers)" when the file has none.
std::string between_markers(const std::string& text, const char* kBegin = kBegin,
                            const char* kEnd = kEnd) {
    const size_t begin = text.find(kBegin);
    if (begin == std::string::npos) return "(no markers)";
    const size_t from = begin + std::string(kBegin).size();
    const size_t end = text.find(kEnd, from);
    return end == std::string::npos ? "(no end marker)" : text.substr(from, end - from);
}

TEST(CheckRegistry, TheDocumentsTablesAreTheRegistrys) {
    const std::string harness = test::read_file(ACETATE_SOURCE_DIR "/docs/harness.md");
    EXPECT_EQ(between_markers(harness), harness_checks_table())
        << "docs/harness.md's table of checks differs from harness/checks.cpp; between the "
           "markers it should read:\n"
        << harness_checks_table();
    const std::string contract = test::read_file(ACETATE_SOURCE_DIR "/docs/contract.md");
    EXPECT_EQ(between_markers(contract), contract_checks_table())
        << "docs/contract.md's table of checks differs from harness/checks.cpp; between the "
           "markers it should read:\n"
        << contract_checks_table();
}

TEST(CheckRegistry, NamesAreUniqueAndWaiversAcceptExactlyTheWaivableOnes) {
    std::set<std::string> names, waivable;
    for (const CheckInfo& c : registered_checks()) {
        EXPECT_TRUE(names.insert(std::string(c.name)).second) << c.name << " twice";
        EXPECT_FALSE(c.rule.empty() || c.cases.empty() || c.fails.empty()) << c.name;
        if (c.waivable) waivable.insert(std::string(c.name));
        EXPECT_EQ(find_registered_check(c.name), &c);
    }
    EXPECT_EQ(find_registered_check("no-such-check"), nullptr);
    waivable.insert(kStrictnessWaiver);
    const auto& accepted = waivable_checks();
    EXPECT_EQ(std::set<std::string>(accepted.begin(), accepted.end()), waivable);
    // A crash, a hang, a refused load and a flaky verdict are never waived.
    for (const char* never : {"process", "load", "repeat"})
        EXPECT_FALSE(find_registered_check(never)->waivable) << never;
}

// Every enumerator of CaseKind (they count up from 0): the switch has no default, so the build
// (-Werror=switch) stops when one is added and not listed here.
std::set<int> every_case_kind() {
    std::set<int> all;
    for (int i = 0;; ++i) {
        switch (CaseKind(i)) {
            case CaseKind::Contract:
            case CaseKind::Determinism:
            case CaseKind::StateIsolation:
            case CaseKind::FloorIsolation:
            case CaseKind::Disconnected:
            case CaseKind::Integration:
            case CaseKind::Golden:
                all.insert(i);
                continue;
        }
        return all;
    }
}

TEST(CaseKindRegistry, TheDocumentsTableIsTheRegistrys) {
    const std::string harness = test::read_file(ACETATE_SOURCE_DIR "/docs/harness.md");
    EXPECT_EQ(between_markers(harness, kKindsBegin, kKindsEnd), harness_case_kinds_table())
        << "docs/harness.md's table of case kinds differs from harness/case_kinds.cpp; between "
           "the markers it should read:\n"
        << harness_case_kinds_table();
}

TEST(CaseKindRegistry, EveryKindIsRegisteredOnceAndReadBackByItsName) {
    std::set<std::string> names;
    std::set<int> kinds;
    for (const CaseKindInfo& k : registered_case_kinds()) {
        EXPECT_TRUE(names.insert(std::string(k.name)).second) << k.name << " twice";
        EXPECT_TRUE(kinds.insert(int(k.kind)).second) << k.name << ": its kind twice";
        EXPECT_TRUE(k.plan && k.run && !k.summary.empty()) << k.name;
        EXPECT_EQ(&case_kind_info(k.kind), &k);
        EXPECT_EQ(find_case_kind(k.name), &k);
        // A case of this kind written to case.json reads back as this kind.
        CaseSpec spec;
        spec.id = "a/case";
        spec.kind = k.kind;
        EXPECT_EQ(read_case_spec(to_json(spec), "case.json").kind, k.kind) << k.name;
    }
    // Every enumerator is registered.
    EXPECT_EQ(kinds, every_case_kind());
    EXPECT_EQ(find_case_kind("no-such-kind"), nullptr);
}

}  // namespace
}  // namespace acetate::harness
