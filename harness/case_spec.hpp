#pragma once
// The harness's cases: what the plugin under test declares (PluginInfo, read in a child
// process so a crashing entry point cannot take the harness down), and the scenarios it is run
// on (CaseSpec), chosen by strictness and seeded so a failing case can be re-run exactly.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace acetate::harness {

struct ParamInfo {
    std::string name;
    std::string type;  // "float", "int", "bool", "vec2", "vec3", "color"
    float default_value = 0, min_value = 0, max_value = 0;
    uint32_t components = 1;  // 2 or 3 for a vector: the harness sets every component alike
};

// A scene of the plugin's own, beside the shared reference scene (references.hpp): a scene file
// under <references>/<plugin id>/scenes/ that uses only this plugin, rendered as written.
struct ReferenceScene {
    std::string name;                // the file's stem: cases "reference/scene-<name>/..."
    std::string file;                // absolute
    std::string digest;              // SHA-256 of the scene file and every image it names, in order
    uint32_t width = 0, height = 0;  // its canvas
};

struct PluginInfo {
    std::string file;  // absolute
    std::string id, version, display_name;
    std::string scope;     // "floor" / "global"
    std::string coverage;  // "preserving" / "expanding"
    std::vector<std::string> masks;
    std::vector<ParamInfo> params;           // what scenes may set (the harness varies these)
    std::vector<std::string> hidden_params;  // set by presets only (ABI 1.1): not varied
    std::vector<std::string> presets;
    std::string abi;  // "1.0", "1.1": what the plugin was built against
    // How far a render at another scale may stray (ABI 1.2's scale_tolerance; camera-scale).
    float scale_tolerance = 0;
    std::string source_digest, binary_sha256;
    // Not declared by the plugin: found beside its references (find_reference_scenes), and
    // carried with it so every process (and a merge) plans the same reference cases.
    std::vector<ReferenceScene> reference_scenes;

    bool is_global() const { return scope == "global"; }
    bool is_expanding() const { return coverage == "expanding"; }
};
nlohmann::json to_json(const PluginInfo& info);
Result<PluginInfo> plugin_info_from_json(const nlohmann::json& json, std::string_view name);
// The same inside another reader of the one field reader (core/json_fields.hpp): the info at
// `path`; a bad field throws json_fields::JsonFieldError, for that reader's read_json to catch.
PluginInfo read_plugin_info(const nlohmann::json& json, const std::string& path);

// What a case does with the plugin: each kind is registered once, with its name, plan and run
// functions, in case_kinds.cpp.
enum class CaseKind {
    Contract,        // render, then check each output against its input (contract_checks.hpp)
    Determinism,     // two frames in one process must match; the digest is compared across two
    StateIsolation,  // floors 0, 1, 0; a floor alone; a second load; memory over many switches
    FloorIsolation,  // the composite with and without the effect, away from its floor
    Disconnected,    // every parameter at min and at max must change something
    Integration,     // with the other integrated plugins, against a CPU-built reference
    Golden,          // a fixed scene rendered and compared with the blessed reference image
};
const char* to_string(CaseKind kind);

// An input pattern the tiles are made of (synthetic_inputs.hpp).
enum class Pattern { Standard, AlphaRamp, Hdr, Empty, Opaque, Subnormal };
const char* to_string(Pattern pattern);
// The lights every floor has (synthetic_inputs.hpp): three over the canvas, none, one, more
// than any preset's cap, off the canvas, with a tiny radius, with a huge one; a sun at 40
// degrees, on the horizon (0) and overhead (90); lights on the floor (height exactly 0) at
// whole-pixel corners of the canvas; lights and a sun of colour 0 and intensity 0.
enum class LightSet {
    Standard,
    None,
    One,
    Many,
    OffCanvas,
    Tiny,
    Huge,
    Sun,
    GrazingSun,
    ZenithSun,
    OnTheFloor,
    Dark,
};
inline constexpr int kLightSetCount = 12;
const char* to_string(LightSet lights);
// What the tiles' masks hold, for each kind the plugin reads: varying content, no mask at all
// (the host gives a transparent texture), all 0, all 1, content on half the tile only, values
// from 1 to 4 (masks are data: the format does not bound them), one-pixel lines of 1 on 0
// (along the tile's edges too).
enum class MaskFill { Content, Absent, Empty, Full, Partial, AboveOne, Thin };
inline constexpr int kMaskFillCount = 7;
const char* to_string(MaskFill masks);
// The floors' names and tiles: "floor<N>" with one tile each; names of 300 characters; names
// outside ASCII (UTF-8); the top floor without any tile.
enum class FloorVariant { Standard, LongNames, UnicodeNames, TopFloorEmpty };
inline constexpr int kFloorVariantCount = 4;
const char* to_string(FloorVariant floors);
// What fills memory a plugin may read before writing it (intermediate targets, `result`): it
// differs between processes, so reading it fails `finite` (NaN) or `determinism` (two finite
// values), instead of happening to read zeros. docs/harness.md, "Poisoned memory".
enum class Poison { None, NaN, Large, Plain };
const char* to_string(Poison poison);

// The format of the floors' targets, their tiles and the intermediate targets an effect
// declares in the floor's format: what a host picks (SceneOptions::precision).
enum class TargetFormat { Rgba16f, Rgba32f };
const char* to_string(TargetFormat format);
// A relation that needs no oracle (relation_checks.cpp), checked in a contract case besides the
// contract: the plugin's floors on a canvas grown to the right and below are unchanged; the
// same scene in rgba16f and rgba32f agrees within half precision; the same scene seen through
// a camera whose region is shifted (ABI 1.2) shows the same pixels where the canvas lands; a
// camera at scale 1/2 shows what the whole render has there, within the declared tolerance.
enum class Relation { None, CanvasSize, FormatAgreement, CameraRegion, CameraScale };
const char* to_string(Relation relation);

// Another plugin an integration case runs beside the one under test.
struct CompanionPlugin {
    std::string id, file, scope;
    // The bytes the registry recorded for it: the case's child loads the companion only if
    // its sealed copy hashes to this (case_session.cpp).
    std::string binary_sha256;
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
    double time = 0;        // seconds; double, as a host passes it (a fraction can round up to 1)
    uint32_t switches = 0;  // StateIsolation: floor switches for the memory check
    std::vector<CompanionPlugin> companions;  // Integration; and the neighbours' files
    // Contexts (docs/harness.md, "Contexts"): the harness's neighbour effects (neighbours.hpp)
    // placed before and after the plugin on each floor that carries it (or among the global
    // effects), by id. The contract is judged on the plugin's own input and output.
    std::vector<std::string> effects_before, effects_after;
    TargetFormat format = TargetFormat::Rgba16f;
    Relation relation = Relation::None;  // Contract

    // The rest of the input model (docs/harness.md, "The input model").
    LightSet lights = LightSet::Standard;
    MaskFill masks = MaskFill::Content;
    FloorVariant floor_variant = FloorVariant::Standard;
    int32_t plugin_floor = -1;  // a floor effect on this floor only; -1: on every floor
    uint32_t frames = 1;        // frames rendered in the load, the last one checked
    uint32_t prior_loads = 0;   // other scenes loaded and rendered in the process first
    // Whether the case's process loads the Khronos validation layer. A case without it runs in
    // a process started afresh (not forked from the server, which loaded the layer), as users
    // run their hosts; its output is compared with the same case's output with the layer.
    bool validation_layer = true;
    // Contract: parameter sets rendered one after the other in this process, each in a load of
    // its own (a parameter swept over its range); empty: `params` alone.
    std::vector<nlohmann::json> sweep;
    Poison poison = Poison::NaN;
    // The input model's dimensions and this case's value of each, for the report.
    std::map<std::string, std::string> inputs;
    // Golden: the blessed image to compare with and its gates (references.hpp,
    // ReferenceGates); null when none is blessed for this source (the case only renders).
    nlohmann::json reference = nullptr;
    // Golden: the plugin's own reference scene, rendered as written (its effects' params and
    // presets), the composite read back; empty: the shared reference scene.
    std::string scene_file;
};
nlohmann::json to_json(const CaseSpec& spec);
Result<CaseSpec> case_spec_from_json(const nlohmann::json& json, std::string_view name);
// The same inside another reader (see read_plugin_info).
CaseSpec read_case_spec(const nlohmann::json& json, const std::string& path);

// The cases of one run (case_kinds.cpp asks each kind; case_plan.cpp plans the contract cases):
// each dimension of the input model varied on its own, then combinations: pairwise, or from a
// Latin hypercube at low strictness. Strictness 1..10 sets how many combinations, sweep
// points, frames and floor switches, and how large the large size;
// `run_seed` makes every case's seed (and so its inputs and drawn values) reproducible.
// `integration` adds the INTEGRATED stage's cases.
std::vector<CaseSpec> plan_cases(const PluginInfo& plugin, int strictness, uint64_t run_seed,
                                 bool alpha_stage, bool integration_stage,
                                 const std::vector<CompanionPlugin>& companions);

// From this strictness on, the combined cases are a pairwise covering array over every
// dimension (combinations.hpp); below it, Latin hypercube points.
inline constexpr int kPairwiseStrictness = 4;
// One line for the report: how this run combines the dimensions (strength, pairs, cases).
std::string combinations_summary(const PluginInfo& plugin, int strictness, uint64_t run_seed);

// SplitMix64's mixing function: a well-spread 64-bit hash of `x`.
uint64_t splitmix64(uint64_t x);

// A case's seed from the run's seed and its id (splitmix64 of both), so adding a case does not
// change the others' seeds.
uint64_t case_seed(uint64_t run_seed, const std::string& case_id);

}  // namespace acetate::harness
