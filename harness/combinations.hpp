#pragma once
// The combined cases (docs/harness.md, "Combinations"): every dimension of the input model as a
// factor with its edge values as levels, and a pairwise covering array over them (pairwise.hpp),
// so every value of every dimension meets every value of every other dimension in some case:
// each preset with each parameter at its minimum, default and maximum, each component of a
// vector or colour parameter on its own, each light set with each mask fill, and so on.

#include <cstdint>
#include <string>
#include <vector>

#include "case_spec.hpp"

namespace acetate::harness {

struct CombinationFactor {
    std::string name;                 // "lights", "params.tint[1]", ...
    std::vector<std::string> levels;  // as the report names them
};

// The factors for this plugin: the dimensions it can observe (a global effect has no lights,
// masks only if declared), its parameters (a vector's components apart) and its presets.
std::vector<CombinationFactor> combination_factors(const PluginInfo& plugin);

struct Combinations {
    std::vector<CaseSpec> cases;  // "combined/pairwise-N", contract cases
    std::string summary;          // the strength, the factors, the pairs and the cases
};
// The pairwise cases, seeded by the run: strength 2 over combination_factors(plugin).
Combinations pairwise_combinations(const PluginInfo& plugin, uint64_t run_seed);

}  // namespace acetate::harness
