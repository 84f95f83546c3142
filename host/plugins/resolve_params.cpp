#include "plugins/resolve_params.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace acetate {
namespace {

std::string known_params(const EffectDescriptor& d) {
    std::string known;
    for (const EffectParam& p : d.params)
        if (!p.hidden) known += (known.empty() ? "" : ", ") + p.name;
    return known.empty() ? "none" : known;
}

// A JSON number as a double; for a scalar parameter also true/false (1/0). A vector or colour
// component must be a number: docs/scene-format.md says "an array of exactly 2 or 3 numbers".
// Any finite number is taken, however large: the caller clamps it to the parameter's range, as
// that document promises ("1e39" for a float parameter becomes its max), so only the shape and
// finiteness are errors here.
Result<double> number_of(const nlohmann::json& value, const std::string& field,
                         bool boolean_allowed) {
    if (value.is_boolean() && boolean_allowed) return value.get<bool>() ? 1.0 : 0.0;
    if (!value.is_number())
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: expected a number, got {}", field, value.dump()));
    const double number = value.get<double>();
    if (!std::isfinite(number))
        return make_error(ErrorCode::InvalidInput, field + ": not a finite number");
    return number;
}

}  // namespace

namespace {

// An error about the entry's field `field` ("floors[0].effects[0].params.day").
Error in_field(Error error, const std::string& scene_file, std::string field) {
    error.file = scene_file;
    error.field = std::move(field);
    return error;
}

}  // namespace

Result<ParamVectors> resolve_param_vectors(const EffectDescriptor& d, const EffectRef& ref,
                                           const std::string& scene_file) {
    ParamVectors values;
    for (const EffectParam& p : d.params) {
        values.push_back(p.default_vector);
        values.back()[0] = p.default_value;
    }
    // Fitted in double, then stored: a value beyond the float range is clamped, never
    // turned into an infinity first.
    auto set = [&](size_t index, uint32_t component, double value) {
        const EffectParam& p = d.params[index];
        if (p.type == ACETATE_PARAM_INT) value = std::round(value);
        if (p.type == ACETATE_PARAM_BOOL) value = value >= 0.5 ? 1.0 : 0.0;
        values[index][component] =
            float(std::clamp(value, double(p.min_value), double(p.max_value)));
    };
    if (!ref.preset.empty()) {
        const auto preset = d.presets.find(ref.preset);
        if (preset == d.presets.end()) {
            std::string known;
            for (const auto& [name, unused] : d.presets)
                known += (known.empty() ? "" : ", ") + name;
            return in_field(
                make_error(ErrorCode::InvalidInput,
                           fmt::format("{}: {}.preset: plugin \"{}\" has no preset \"{}\" "
                                       "(it has: {})",
                                       scene_file, ref.where, d.id, ref.preset,
                                       known.empty() ? "none" : known)),
                scene_file, ref.where + ".preset");
        }
        for (const auto& [name, value] : preset->second) set(size_t(d.param_index(name)), 0, value);
    }
    for (const auto& [name, value] : ref.params.items()) {
        const std::string field = fmt::format("{}: {}.params.{}", scene_file, ref.where, name);
        const std::string param_field = ref.where + ".params." + name;
        const auto refused = [&](Error error) {
            return in_field(std::move(error), scene_file, param_field);
        };
        const int index = d.param_index(name);
        if (index < 0)
            return refused(
                make_error(ErrorCode::InvalidInput,
                           fmt::format("{}: plugin \"{}\" has no such parameter (it has: {})",
                                       field, d.id, known_params(d))));
        const EffectParam& p = d.params[size_t(index)];
        if (p.hidden)
            return refused(
                make_error(ErrorCode::InvalidInput,
                           fmt::format("{}: plugin \"{}\" sets this parameter from its presets "
                                       "only; choose a preset instead",
                                       field, d.id)));
        const uint32_t components = p.components();
        if (components == 1) {
            auto number = number_of(value, field, true);
            if (!number) return refused(number.error());
            set(size_t(index), 0, number.value());
            continue;
        }
        if (!value.is_array() || value.size() != components)
            return refused(make_error(ErrorCode::InvalidInput,
                                      fmt::format("{}: expected an array of {} numbers, got {}",
                                                  field, components, value.dump())));
        for (uint32_t c = 0; c < components; ++c) {
            auto number = number_of(value[c], fmt::format("{}[{}]", field, c), false);
            if (!number) return refused(number.error());
            set(size_t(index), c, number.value());
        }
    }
    return values;
}

Result<std::vector<float>> resolve_params(const EffectDescriptor& d, const EffectRef& ref,
                                          const std::string& scene_file) {
    auto vectors = resolve_param_vectors(d, ref, scene_file);
    if (!vectors) return vectors.error();
    std::vector<float> scalars;
    for (const auto& v : vectors.value()) scalars.push_back(v[0]);
    return scalars;
}

}  // namespace acetate
