#pragma once
// What a case kind's plan function is given (case_kinds.hpp): the plugin, the run's strictness
// and seed, the integrated companions, and the Planner that collects the cases in order.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "case_spec.hpp"
#include "input_model.hpp"

namespace acetate::harness {

struct PlanContext {
    const PluginInfo& plugin;
    int strictness = 5;  // 1..10
    uint64_t run_seed = 0;
    const std::vector<CompanionPlugin>& companions;  // the integrated plugins (integration stage)
    bool floor_effect() const { return !plugin.is_global(); }
};

class Planner {
  public:
    Planner(const PluginInfo& plugin, uint64_t run_seed) : plugin_(plugin), run_seed_(run_seed) {}

    // A contract case of that id and size, the rest at its defaults, for the caller to vary.
    CaseSpec contract(std::string id, std::string description, uint32_t w = 128, uint32_t h = 96,
                      Pattern pattern = Pattern::Standard, uint32_t floors = 1) const {
        CaseSpec s;
        s.id = std::move(id);
        s.description = std::move(description);
        s.width = w;
        s.height = h;
        s.pattern = pattern;
        s.floors = floors;
        return s;
    }
    // Seeds the case from its id (unless it was seeded already), poisons it, and tabulates
    // its inputs for the report.
    void add(CaseSpec s, bool seeded = false) {
        if (!seeded) s.seed = case_seed(run_seed_, s.id);
        // NaN in most processes (reading it fails `finite`); a large finite colour in every
        // third, so a plugin that launders NaN still shows a difference somewhere.
        if (s.poison == Poison::NaN && cases.size() % 3 == 2) s.poison = Poison::Large;
        s.inputs = describe_inputs(s, plugin_);
        cases.push_back(std::move(s));
    }
    // Adds a case exactly as it is: one that is the same at every seed (a golden reference).
    void add_as_is(CaseSpec s) { cases.push_back(std::move(s)); }

    std::vector<CaseSpec> cases;

  private:
    const PluginInfo& plugin_;
    uint64_t run_seed_;
};

}  // namespace acetate::harness
