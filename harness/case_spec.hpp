#pragma once
// The harness's cases: what the plugin under test declares (PluginInfo, read in a child
// process so a crashing entry point cannot take the harness down), and the scenarios it is run
// on (CaseSpec), chosen by strictness and seeded so a failing case can be re-run exactly.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace acetate::harness {

struct ParamInfo {
    std::string name;
    std::string type;  // "float", "int", "bool"
    float default_value = 0, min_value = 0, max_value = 0;
};

struct PluginInfo {
    std::string file;  // absolute
    std::string id, version, display_name;
    std::string scope;     // "floor" / "global"
    std::string coverage;  // "preserving" / "expanding"
    std::vector<std::string> masks;
    std::vector<ParamInfo> params;
    std::vector<std::string> presets;
    std::string source_digest, binary_sha256;

    bool is_global() const { return scope == "global"; }
    bool is_expanding() const { return coverage == "expanding"; }
};
nlohmann::json to_json(const PluginInfo& info);
Result<PluginInfo> plugin_info_from_json(const nlohmann::json& json, std::string_view name);

// What a case does with the plugin (case_runner.cpp runs each kind).
enum class CaseKind {
    Contract,        // render, then check each output against its input (contract_checks.hpp)
    Determinism,     // two frames in one process must match; the digest is compared across two
    StateIsolation,  // floors 0, 1, 0; a floor alone; a second load; memory over many switches
    FloorIsolation,  // the composite with and without the effect, away from its floor
    Disconnected,    // every parameter at min and at max must change something
    Integration,     // with the other integrated plugins, against a CPU-built reference
};
const char* to_string(CaseKind kind);

// An input pattern the tiles are made of (synthetic_inputs.hpp).
enum class Pattern { Standard, AlphaRamp, Hdr, Empty, Opaque };
const char* to_string(Pattern pattern);

// Another plugin an integration case runs beside the one under test.
struct CompanionPlugin {
    std::string id, file, scope;
};

struct CaseSpec {
    std::string id;           // "sizes/1x1"
    std::string description;  // one line for people
    CaseKind kind = CaseKind::Contract;
    uint64_t seed = 0;  // the case's own seed: inputs, lights, random parameters, time
    uint32_t width = 256, height = 160;
    Pattern pattern = Pattern::Standard;
    uint32_t floors = 1;  // the plugin runs on every floor (a floor effect) or once on the
                          // composite (a global one), unless the kind says otherwise
    nlohmann::json params = nlohmann::json::object();  // scene params of the plugin under test
    std::string preset;
    float time = 0;
    uint32_t switches = 0;                    // StateIsolation: floor switches for the memory check
    std::vector<CompanionPlugin> companions;  // Integration
};
nlohmann::json to_json(const CaseSpec& spec);
Result<CaseSpec> case_spec_from_json(const nlohmann::json& json, std::string_view name);

// The cases of one run. Strictness 1..10 sets how many parameter seeds, how large the large
// size and how many floor switches; `run_seed` makes every case's seed (and so its inputs and
// random parameters) reproducible. `integration` adds the INTEGRATED stage's cases.
std::vector<CaseSpec> plan_cases(const PluginInfo& plugin, int strictness, uint64_t run_seed,
                                 bool alpha_stage, bool integration_stage,
                                 const std::vector<CompanionPlugin>& companions);

// A case's seed from the run's seed and its id (splitmix64 of both), so adding a case does not
// change the others' seeds.
uint64_t case_seed(uint64_t run_seed, const std::string& case_id);

}  // namespace acetate::harness
