// The harness's pure parts beside the contract checks, directly: the case planner
// (plan_cases: deterministic for a seed, unique ids, every parameter swept, more cases with more
// strictness, a case's seed independent of the others), which cases share a child process
// (group_cases: in order, each once, the cases that judge the process alone) and the waivers
// (apply_waivers: a waived
// FAIL reads WAIVED, an expired waiver fails the run, process failures are never waived). The
// battery proves the same through whole runs; these name the rule. No device.

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "case_batch.hpp"
#include "case_kinds.hpp"
#include "case_spec.hpp"
#include "report_fixtures.hpp"
#include "waivers.hpp"

namespace acetate::harness {
namespace {

using report_test::case_with;
using report_test::check;

PluginInfo sample_plugin() {
    PluginInfo p;
    p.file = "/plugins/glow.so";
    p.id = "com.example.glow";
    p.version = "1.0.0";
    p.scope = "floor";
    p.coverage = "preserving";
    p.masks = {"water"};
    p.params = {{"gain", "float", 1.0f, 0.0f, 4.0f, 1}, {"taps", "int", 2.0f, 1.0f, 8.0f, 1}};
    p.presets = {"low", "high"};
    p.abi = "1.1";
    p.source_digest = std::string(64, 'a');
    p.binary_sha256 = std::string(64, 'b');
    return p;
}

std::vector<std::string> ids(const std::vector<CaseSpec>& cases) {
    std::vector<std::string> out;
    for (const CaseSpec& c : cases) out.push_back(c.id);
    return out;
}

TEST(CasePlan, TheSameSeedPlansTheSameCasesAndIdsAreUnique) {
    const PluginInfo plugin = sample_plugin();
    const auto a = plan_cases(plugin, 5, 42, true, false, {});
    const auto b = plan_cases(plugin, 5, 42, true, false, {});
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(ids(a), ids(b));
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].seed, b[i].seed) << a[i].id;
        EXPECT_EQ(a[i].params, b[i].params) << a[i].id;
    }
    const auto list = ids(a);
    EXPECT_EQ(std::set<std::string>(list.begin(), list.end()).size(), list.size());
}

TEST(CasePlan, EveryParameterIsSweptAndEveryPresetTried) {
    const auto cases = plan_cases(sample_plugin(), 5, 1, true, false, {});
    std::set<std::string> all;
    for (const CaseSpec& c : cases) all.insert(c.id);
    for (const char* name : {"gain", "taps"})
        EXPECT_TRUE(all.count(std::string("params/sweep-") + name)) << name;
    for (const char* preset : {"low", "high"})
        EXPECT_TRUE(all.count(std::string("params/preset-") + preset)) << preset;
}

TEST(CasePlan, MoreStrictnessPlansMoreCasesAndAnotherSeedOtherDraws) {
    const PluginInfo plugin = sample_plugin();
    const size_t at1 = plan_cases(plugin, 1, 1, true, false, {}).size();
    const size_t at5 = plan_cases(plugin, 5, 1, true, false, {}).size();
    const size_t at10 = plan_cases(plugin, 10, 1, true, false, {}).size();
    EXPECT_LT(at1, at5);
    EXPECT_LT(at5, at10);
    // A case's seed comes from the run's seed and its own id only.
    EXPECT_EQ(case_seed(7, "sizes/1x1"), case_seed(7, "sizes/1x1"));
    EXPECT_NE(case_seed(7, "sizes/1x1"), case_seed(8, "sizes/1x1"));
    EXPECT_NE(case_seed(7, "sizes/1x1"), case_seed(7, "sizes/odd"));
}

// Every case once, in the plan's order; no process holds more than `per_process`; a case run
// without the layer, or of a kind that judges its process, holds its process alone.
void expect_grouping_holds(const std::vector<CaseSpec>& cases,
                           const std::vector<std::vector<size_t>>& groups, unsigned per_process) {
    size_t next = 0;
    for (const auto& group : groups) {
        ASSERT_FALSE(group.empty());
        EXPECT_LE(group.size(), per_process);
        for (size_t i : group) {
            EXPECT_EQ(i, next) << "out of order or repeated: " << cases.at(i).id;
            ++next;
            const bool alone =
                !cases[i].validation_layer || case_kind_info(cases[i].kind).own_process;
            if (alone) {
                EXPECT_EQ(group.size(), 1u) << cases[i].id << " shares its process";
            }
        }
    }
    EXPECT_EQ(next, cases.size());
}

TEST(ProcessGroups, CasesShareProcessesInOrderAndThoseJudgingTheProcessAreAlone) {
    const auto cases = plan_cases(sample_plugin(), 5, 1, true, false, {});
    const auto groups = group_cases(cases, 8, 2);
    expect_grouping_holds(cases, groups, 8);
    // The plan has cases that need a process of their own, and many that share one.
    size_t alone_by_rule = 0, shared = 0;
    for (const auto& group : groups) {
        const CaseSpec& first = cases[group.front()];
        if (!first.validation_layer || case_kind_info(first.kind).own_process) ++alone_by_rule;
        if (group.size() > 1) shared += group.size();
    }
    EXPECT_GE(alone_by_rule, 4u);  // determinism's three processes, state isolation
    EXPECT_GT(shared, cases.size() / 2);
    EXPECT_LT(groups.size(), cases.size() / 2);
}

TEST(ProcessGroups, OnePerProcessAndFewCasesLeaveEveryCaseAlone) {
    const auto cases = plan_cases(sample_plugin(), 5, 1, true, false, {});
    const auto one = group_cases(cases, 1, 2);
    expect_grouping_holds(cases, one, 1);
    EXPECT_EQ(one.size(), cases.size());
    // Eight cases on two jobs: each job gets four processes, so one case each.
    const std::vector<CaseSpec> few(cases.begin(), cases.begin() + 8);
    EXPECT_EQ(group_cases(few, 8, 2).size(), 8u);
    // Sixty-four on two jobs: four processes a job, eight cases each.
    std::vector<CaseSpec> plain(64);
    const auto groups = group_cases(plain, 8, 2);
    expect_grouping_holds(plain, groups, 8);
    EXPECT_EQ(groups.size(), 8u);
}

Waiver waiver(std::string check_name, std::string until) {
    Waiver w;
    w.check = std::move(check_name);
    w.reason = "a known false positive";
    w.by = "alice";
    w.at = "2026-01-01T00:00:00Z";
    w.until = std::move(until);
    w.source_digest = std::string(64, 'a');
    return w;
}

TEST(Waivers, AWaivedFailReadsWaivedAndTheCasePasses) {
    std::vector<CaseResult> results = {
        case_with("sizes/1x1", Verdict::Fail, {check("reach", Verdict::Fail, "cut off")})};
    apply_waivers(results, {waiver("reach", "2026-12-31")}, "2026-11-27");
    ASSERT_EQ(results.size(), 1u);
    EXPECT_EQ(results[0].checks[0].verdict, Verdict::Waived);
    EXPECT_NE(results[0].checks[0].message.find("cut off"), std::string::npos);
    EXPECT_NE(results[0].verdict, Verdict::Fail);
}

TEST(Waivers, AnotherCheckStillFailsAndTheControlWithoutWaiversIsUnchanged) {
    const std::vector<CaseResult> original = {
        case_with("sizes/1x1", Verdict::Fail,
                  {check("reach", Verdict::Fail, "cut off"),
                   check("premultiplied", Verdict::Fail, "colour at alpha 0")})};
    std::vector<CaseResult> results = original;
    apply_waivers(results, {waiver("reach", "2026-12-31")}, "2026-11-27");
    EXPECT_EQ(results[0].checks[1].verdict, Verdict::Fail);
    EXPECT_EQ(results[0].verdict, Verdict::Fail);
    std::vector<CaseResult> control = original;
    apply_waivers(control, {}, "2026-11-27");
    EXPECT_EQ(control[0].checks[0].verdict, Verdict::Fail);
    EXPECT_EQ(control.size(), 1u);
}

TEST(Waivers, AnExpiredWaiverAddsAFailingCaseAndWaivesNothing) {
    std::vector<CaseResult> results = {
        case_with("sizes/1x1", Verdict::Fail, {check("reach", Verdict::Fail, "cut off")})};
    // The last day still holds; the day after does not.
    std::vector<CaseResult> last_day = results;
    apply_waivers(last_day, {waiver("reach", "2026-11-27")}, "2026-11-27");
    EXPECT_EQ(last_day[0].checks[0].verdict, Verdict::Waived);
    apply_waivers(results, {waiver("reach", "2026-11-26")}, "2026-11-27");
    EXPECT_EQ(results[0].checks[0].verdict, Verdict::Fail);
    bool expired_case = false;
    for (const CaseResult& r : results)
        if (r.id == "waivers/expired") expired_case = r.verdict == Verdict::Fail;
    EXPECT_TRUE(expired_case) << "an expired waiver fails the run in a case of its own";
}

TEST(Waivers, ProcessFailuresAreNeverWaived) {
    for (Verdict process : {Verdict::Crash, Verdict::Timeout, Verdict::Flaky}) {
        std::vector<CaseResult> results = {case_with("sizes/1x1", process)};
        apply_waivers(results, {waiver("reach", "2026-12-31")}, "2026-11-27");
        EXPECT_EQ(results[0].verdict, process) << to_string(process);
    }
}

}  // namespace
}  // namespace acetate::harness
