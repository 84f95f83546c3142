// acetate/effect_params.hpp -- parameters and presets of the C++ layer (acetate/effect.hpp
// includes it; include that one).
//
// Declare each parameter once, as a typed constant, and use that one constant everywhere: in
// info() (it converts to Param), in presets, and in build() to read the value with its type
// (floor[kTaps] is an int). A name typed twice can drift apart; a constant cannot.
//
//   inline constexpr acetate::sdk::IntParam kTaps{"taps", "samples per axis", 2, 1, 4};
//   e.params = {kTaps};
//   e.presets = acetate::sdk::quality_presets({{kTaps, {1, 2, 3, 4}}});
//   const int taps = floor[kTaps];
#pragma once

#include <acetate/effect.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace acetate::sdk {

// One parameter as the descriptor lists it. The typed constants below convert to it; a Param
// written out field by field (the ABI 1.0 way) still works.
struct Param {
    std::string name;
    std::string description;
    float default_value = 0, min_value = 0, max_value = 1;
    uint32_t type = ACETATE_PARAM_FLOAT;
    // 1.1. Appended, so 1.0 code's initialisers (designated or positional) still compile.
    uint32_t flags = 0;                     // ACETATE_PARAM_HIDDEN
    std::array<float, 4> default_vector{};  // VEC2, VEC3, COLOR: the default of each component
};

struct Preset {
    // 1 to 32 of [a-z0-9_-], starting with a letter: "low", "medium", "high", "ultra", or any
    // other ("draft", "print"). List them from the cheapest to the best: acetate-bench measures
    // error against "ultra", or against the last one when there is no "ultra".
    std::string name;
    std::vector<std::pair<std::string, float>> values;
};

namespace detail {

inline Param make_param(std::string_view name, std::string_view description, uint32_t type,
                        float default_value, float min_value, float max_value, bool hidden) {
    return {std::string(name),
            std::string(description),
            default_value,
            min_value,
            max_value,
            type,
            hidden ? ACETATE_PARAM_HIDDEN : 0u};
}

// The host wants default_value equal to the first component's default (acetate/effect.h).
template <size_t N>
Param make_vector_param(std::string_view name, std::string_view description, uint32_t type,
                        const std::array<float, N>& default_value, float min_value, float max_value,
                        bool hidden) {
    Param p = make_param(name, description, type, default_value[0], min_value, max_value, hidden);
    for (size_t i = 0; i < N; ++i) p.default_vector[i] = default_value[i];
    return p;
}

}  // namespace detail

// Typed parameters. `hidden`: only presets set it (a quality knob); scenes may not, and the
// harness does not sweep it.
struct FloatParam {
    std::string_view name, description;
    float default_value, min_value, max_value;
    bool hidden = false;
    operator Param() const {
        return detail::make_param(name, description, ACETATE_PARAM_FLOAT, default_value, min_value,
                                  max_value, hidden);
    }
};

// A whole number; the host rounds and clamps it, so build() reads an int.
struct IntParam {
    std::string_view name, description;
    int default_value, min_value, max_value;
    bool hidden = false;
    operator Param() const {
        return detail::make_param(name, description, ACETATE_PARAM_INT, float(default_value),
                                  float(min_value), float(max_value), hidden);
    }
};

struct BoolParam {
    std::string_view name, description;
    bool default_value;
    bool hidden = false;
    operator Param() const {
        return detail::make_param(name, description, ACETATE_PARAM_BOOL,
                                  default_value ? 1.0f : 0.0f, 0.0f, 1.0f, hidden);
    }
};

// Vectors: min_value and max_value bound every component. A scene gives them as JSON arrays;
// GLSL sees param_<name> as a vec2 / vec3. Presets cannot set them (a host rule).
struct Vec2Param {
    std::string_view name, description;
    std::array<float, 2> default_value;
    float min_value, max_value;
    bool hidden = false;
    operator Param() const {
        return detail::make_vector_param(name, description, ACETATE_PARAM_VEC2, default_value,
                                         min_value, max_value, hidden);
    }
};

struct Vec3Param {
    std::string_view name, description;
    std::array<float, 3> default_value;
    float min_value, max_value;
    bool hidden = false;
    operator Param() const {
        return detail::make_vector_param(name, description, ACETATE_PARAM_VEC3, default_value,
                                         min_value, max_value, hidden);
    }
};

// Linear RGB; [0, 1] unless said otherwise (an HDR colour may go higher).
struct ColorParam {
    std::string_view name, description;
    std::array<float, 3> default_value;
    float min_value = 0, max_value = 1;
    bool hidden = false;
    operator Param() const {
        return detail::make_vector_param(name, description, ACETATE_PARAM_COLOR, default_value,
                                         min_value, max_value, hidden);
    }
};

// One scalar parameter's values at the four presets, low to ultra. Typed like the parameter,
// so {kTaps, {1, 2, 3, 4}} takes ints and a vector parameter is a compile error.
struct PresetRow {
    PresetRow(const FloatParam& p, std::array<float, 4> v) : name(p.name), values(v) {}
    PresetRow(const IntParam& p, std::array<int, 4> v)
        : name(p.name), values{float(v[0]), float(v[1]), float(v[2]), float(v[3])} {}
    PresetRow(const BoolParam& p, std::array<bool, 4> v)
        : name(p.name), values{float(v[0]), float(v[1]), float(v[2]), float(v[3])} {}
    std::string_view name;
    std::array<float, 4> values;
};

// The four presets "low", "medium", "high", "ultra", each setting every row's parameter:
//   e.presets = quality_presets({{kTaps, {1, 2, 3, 4}}, {kStrength, {0.2f, 0.4f, 0.6f, 0.8f}}});
inline std::vector<Preset> quality_presets(std::initializer_list<PresetRow> rows) {
    static constexpr const char* kNames[4] = {"low", "medium", "high", "ultra"};
    std::vector<Preset> presets;
    for (size_t i = 0; i < 4; ++i) {
        Preset preset{kNames[i], {}};
        for (const PresetRow& row : rows) preset.values.emplace_back(row.name, row.values[i]);
        presets.push_back(std::move(preset));
    }
    return presets;
}

// One row of named_presets(): a scalar parameter and its value in each of N presets, in the
// order the presets are named.
template <size_t N>
struct NamedPresetRow {
    template <size_t M>
    NamedPresetRow(const FloatParam& p, const float (&v)[M]) : name(p.name) {
        copy(v);
    }
    template <size_t M>
    NamedPresetRow(const IntParam& p, const int (&v)[M]) : name(p.name) {
        copy(v);
    }
    template <size_t M>
    NamedPresetRow(const BoolParam& p, const bool (&v)[M]) : name(p.name) {
        copy(v);
    }
    std::string_view name;
    std::array<float, N> values{};

  private:
    template <class T, size_t M>
    void copy(const T (&v)[M]) {
        static_assert(M == N, "a row holds one value for each preset named");
        for (size_t i = 0; i < N; ++i) values[i] = float(v[i]);
    }
};

// Presets in any number and with any names, cheapest first, each setting every row's
// parameter to its value in that preset (a row with another number of values does not compile):
//   e.presets = named_presets({"draft", "final"}, {{kTaps, {1, 8}}, {kStrength, {0.3f, 0.6f}}});
template <size_t N>
std::vector<Preset> named_presets(const char* const (&names)[N],
                                  std::initializer_list<NamedPresetRow<N>> rows) {
    std::vector<Preset> presets;
    for (size_t i = 0; i < N; ++i) {
        Preset preset{names[i], {}};
        for (const NamedPresetRow<N>& row : rows)
            preset.values.emplace_back(row.name, row.values[i]);
        presets.push_back(std::move(preset));
    }
    return presets;
}

}  // namespace acetate::sdk
