#pragma once
// The kinds of case (CaseKind), each run in the case's child process on an open session; a
// kind adds its checks to the writer. Environment failures come back as errors.

#include "case_session.hpp"

namespace acetate::harness {

// contract_cases.cpp
Result<void> run_contract(const CaseContext& c, Session& s, CaseWriter& w);
Result<void> run_disconnected(const CaseContext& c, Session& s, CaseWriter& w);
// isolation_cases.cpp
Result<void> run_determinism(const CaseContext& c, Session& s, CaseWriter& w);
Result<void> run_state_isolation(const CaseContext& c, Session& s, CaseWriter& w);
Result<void> run_floor_isolation(const CaseContext& c, Session& s, CaseWriter& w);
// golden_case.cpp
Result<void> run_golden(const CaseContext& c, Session& s, CaseWriter& w);
// integration_case.cpp
Result<void> run_integration(const CaseContext& c, Session& s, CaseWriter& w);

}  // namespace acetate::harness
