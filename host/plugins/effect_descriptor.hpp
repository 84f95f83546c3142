#pragma once
// The host's own copy of a plugin's descriptor, checked once at load. Nothing after load reads
// the plugin's C structs again, so a plugin cannot change what it declared.

#include <acetate/effect.h>

#include <array>
#include <map>
#include <string>
#include <vector>

#include "core/plugin_id.hpp"
#include "core/result.hpp"

namespace acetate {

struct EffectParam {
    std::string name, description;
    uint32_t type = ACETATE_PARAM_FLOAT;
    float default_value = 0, min_value = 0, max_value = 0;
    bool hidden = false;                              // 1.1: set by presets only
    std::array<float, 4> default_vector{0, 0, 0, 0};  // x = default_value for a scalar

    // 1 for a scalar, 2 or 3 for ACETATE_PARAM_VEC2 / VEC3 / COLOR.
    uint32_t components() const;
};

struct EffectDescriptor {
    std::string id, display_name, source_digest;
    uint32_t abi_minor = 0;  // the ABI 1.x the plugin was built against
    // 1.2: how far a render at another scale may stray, a fraction of the largest value there
    // (0 when not declared).
    float scale_tolerance = 0;
    uint32_t version[3] = {0, 0, 0};
    uint32_t scope = ACETATE_SCOPE_FLOOR;
    uint32_t coverage = ACETATE_COVERAGE_PRESERVING;
    std::vector<std::string> masks;
    std::vector<EffectParam> params;
    std::map<std::string, std::map<std::string, float>> presets;  // name -> param -> value
    // The presets' names as the plugin declared them: from its cheapest to its best by the
    // SDK's convention (acetate-bench measures error against the last when there is no ultra).
    std::vector<std::string> preset_order;

    int param_index(const std::string& name) const;
    std::string version_string() const;
};

// The most a descriptor may declare as its scale_tolerance: past four times the largest value
// around a pixel, the relation would say nothing.
inline constexpr float kMaxScaleTolerance = 4;

// The ABI version a plugin asks for, read before anything else so that a plugin newer than the
// host is refused with both versions named rather than with a field it cannot read.
std::string abi_version_string(uint32_t minor);

// Copies and checks a descriptor: struct size, ABI version (a plugin built for a newer 1.x than
// this host is refused: `x.so: built for Acetate ABI 1.2; this host supports ABI 1.1`), id
// (reverse-DNS), names, scope, coverage, every parameter's range and default, every preset's names
// and values. The error names `where` (the plugin file) and the field, e.g. `lighting.so: params[2]
// "darkness": default 1.5 is outside [0, 1]`.
Result<EffectDescriptor> copy_descriptor(const AcetateEffectDescriptor* descriptor,
                                         const std::string& where);

// [a-z][a-z0-9_]* -- the names of parameters, targets, passes and mask kinds.
bool is_simple_name(const std::string& name);
// A preset's name: 1 to kMaxPresetNameLength of [a-z0-9_-], starting with a letter ("low",
// "ultra", "draft", "print-300dpi"): a scene file and a command line name it.
inline constexpr size_t kMaxPresetNameLength = 32;
bool is_preset_name(const std::string& name);

}  // namespace acetate
