#pragma once
// An effect's parameter values for one instance: defaults, then the preset, then the scene's
// params, each clamped to its range. CPU only (tests/unit/resolve_params_test.cpp runs it without a
// device).

#include <array>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "plugins/effect_descriptor.hpp"
#include "scene/scene.hpp"

namespace acetate {

// One value per parameter, 4 floats each: a scalar in x (the rest 0), a vector's components.
using ParamVectors = std::vector<std::array<float, 4>>;

// Errors name the scene file and field: an unknown preset or parameter, a value that is not a
// number (or, for a vector parameter, not an array of that many numbers), a hidden parameter
// (ACETATE_PARAM_HIDDEN: presets only) set by the scene.
Result<ParamVectors> resolve_param_vectors(const EffectDescriptor& descriptor, const EffectRef& ref,
                                           const std::string& scene_file);

// The same, scalars only: each parameter's x (what ABI 1.0 passes in AcetateFloorInfo::params).
Result<std::vector<float>> resolve_params(const EffectDescriptor& descriptor, const EffectRef& ref,
                                          const std::string& scene_file);

}  // namespace acetate
