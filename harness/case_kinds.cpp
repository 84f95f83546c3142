#include "case_kinds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdlib>

namespace acetate::harness {
namespace {

constexpr std::array kCaseKinds = {
    CaseKindInfo{CaseKind::Contract, "contract", ValidationStage::AlphaTested,
                 "renders a scene (one dimension at its edge, a context, a relation or a "
                 "combination) and checks each output against its input",
                 plan_contract, run_contract},
    CaseKindInfo{CaseKind::Determinism, "determinism", ValidationStage::AlphaTested,
                 "renders one scene twice in each of three processes, one after other scenes; "
                 "every frame must give the same bytes",
                 plan_determinism, run_determinism, /*own_process=*/true},
    CaseKindInfo{CaseKind::StateIsolation, "state-isolation", ValidationStage::AlphaTested,
                 "floors 0, 1, 0, each floor alone and a second load must agree; then many "
                 "floor switches and loads for memory growth",
                 plan_state_isolation, run_state_isolation, /*own_process=*/true},
    CaseKindInfo{CaseKind::FloorIsolation, "floor-isolation", ValidationStage::AlphaTested,
                 "the composite with and without the effect on floor 1 of 3, compared where "
                 "that floor covers nothing (floor effects)",
                 plan_floor_isolation, run_floor_isolation},
    CaseKindInfo{CaseKind::Disconnected, "disconnected", ValidationStage::AlphaTested,
                 "sweeps each parameter over its range; some two values must change the output",
                 plan_disconnected, run_disconnected},
    CaseKindInfo{CaseKind::Golden, "golden", ValidationStage::AlphaTested,
                 "renders a fixed scene and compares it with the blessed reference image",
                 plan_golden, run_golden},
    CaseKindInfo{CaseKind::Integration, "integration", ValidationStage::Integrated,
                 "four floors with the other integrated plugins, against the composite "
                 "rebuilt from each floor rendered alone",
                 plan_integration, run_integration},
};

}  // namespace

std::span<const CaseKindInfo> registered_case_kinds() {
    return kCaseKinds;
}

const CaseKindInfo& case_kind_info(CaseKind kind) {
    for (const CaseKindInfo& info : kCaseKinds)
        if (info.kind == kind) return info;
    std::abort();  // every enumerator is registered (check_registry_test.cpp)
}

const CaseKindInfo* find_case_kind(std::string_view name) {
    for (const CaseKindInfo& info : kCaseKinds)
        if (info.name == name) return &info;
    return nullptr;
}

const char* to_string(CaseKind kind) {
    return case_kind_info(kind).name.data();
}

std::string harness_case_kinds_table() {
    std::string table = "| kind | stage | process | what a case does |\n|---|---|---|---|\n";
    for (const CaseKindInfo& k : kCaseKinds)
        table += fmt::format("| `{}` | {} | {} | {} |\n", k.name,
                             k.stage == ValidationStage::Integrated ? "integrated" : "alpha-tested",
                             k.own_process ? "its own" : "shared", k.summary);
    return table;
}

std::vector<CaseSpec> plan_cases(const PluginInfo& plugin, int strictness, uint64_t run_seed,
                                 bool alpha_stage, bool integration_stage,
                                 const std::vector<CompanionPlugin>& companions) {
    const PlanContext context{plugin, std::clamp(strictness, 1, 10), run_seed, companions};
    Planner p(plugin, run_seed);
    for (const CaseKindInfo& kind : kCaseKinds)
        if (kind.stage == ValidationStage::Integrated ? integration_stage : alpha_stage)
            kind.plan(context, p);
    return p.cases;
}

}  // namespace acetate::harness
