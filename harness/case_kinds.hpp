#pragma once
// Every kind of case, registered once (case_kinds.cpp): its name in case.json, the stage whose
// cases it plans, one line for docs/harness.md, and its plan and run functions. The planner asks
// every kind for its cases in this order (plan_cases); a case's child runs its kind's `run` on
// an open session, which adds the kind's checks to the writer (environment failures come back
// as errors). tests/unit/check_registry_test.cpp keeps docs/harness.md's table of kinds equal to
// the registry. Adding a kind: docs/harness.md, "Adding a check".

#include <span>
#include <string>
#include <string_view>

#include "case_session.hpp"
#include "planner.hpp"
#include "registry.hpp"

namespace acetate::harness {

struct CaseKindInfo {
    CaseKind kind;
    std::string_view name;     // case.json's "kind"
    ValidationStage stage;     // AlphaTested or Integrated: the stage whose cases it plans
    std::string_view summary;  // what a case of this kind does (Markdown, one line)
    void (*plan)(const PlanContext& context, Planner& planner);
    Result<void> (*run)(const CaseContext& c, Session& s, CaseWriter& w);
    // Its case starts a child process of its own instead of following other cases in one
    // (case_batch.hpp): it judges the process itself (the same bytes in three processes,
    // memory growth), which the cases before it would change.
    bool own_process = false;
};

// In the order a run lists their cases.
std::span<const CaseKindInfo> registered_case_kinds();
const CaseKindInfo& case_kind_info(CaseKind kind);
// The kind of that name; null when there is none.
const CaseKindInfo* find_case_kind(std::string_view name);
// docs/harness.md's "| kind | stage | what a case does |" table, between its "case kinds" markers.
std::string harness_case_kinds_table();

// Each kind's plan and run functions, by file.
// case_plan.cpp: every dimension of the input model on its own, contexts, relations, combinations
void plan_contract(const PlanContext& context, Planner& p);
// contract_cases.cpp
Result<void> run_contract(const CaseContext& c, Session& s, CaseWriter& w);
void plan_disconnected(const PlanContext& context, Planner& p);
Result<void> run_disconnected(const CaseContext& c, Session& s, CaseWriter& w);
// isolation_cases.cpp
void plan_determinism(const PlanContext& context, Planner& p);
Result<void> run_determinism(const CaseContext& c, Session& s, CaseWriter& w);
void plan_state_isolation(const PlanContext& context, Planner& p);
Result<void> run_state_isolation(const CaseContext& c, Session& s, CaseWriter& w);
void plan_floor_isolation(const PlanContext& context, Planner& p);
Result<void> run_floor_isolation(const CaseContext& c, Session& s, CaseWriter& w);
// golden_case.cpp
void plan_golden(const PlanContext& context, Planner& p);
Result<void> run_golden(const CaseContext& c, Session& s, CaseWriter& w);
// integration_case.cpp
void plan_integration(const PlanContext& context, Planner& p);
Result<void> run_integration(const CaseContext& c, Session& s, CaseWriter& w);

}  // namespace acetate::harness
