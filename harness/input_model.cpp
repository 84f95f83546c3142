#include "input_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace acetate::harness {
namespace {

const char* parity(uint32_t n) {
    return n % 2 ? "odd" : "even";
}

// A category from a unit coordinate: stratified coordinates give balanced categories.
template <class Enum>
Enum category(double u, int count) {
    return Enum(std::clamp(int(u * count), 0, count - 1));
}

// Log-spaced integer in [1, max]: small sizes are where odd rounding lives.
uint32_t log_size(double u, double max) {
    return uint32_t(std::clamp(std::lround(std::exp(u * std::log(max))), 1l, long(max)));
}

// Negative times (-100 to -0.01 s) on the first fifth of the axis, then 0.01 s to 10^5 s,
// log-spaced: large times are where single-precision phase arithmetic breaks.
float time_at(double u) {
    if (u < 0.2) return -float(std::pow(10.0, -2.0 + 4.0 * (u / 0.2)));
    return float(std::pow(10.0, -2.0 + 7.0 * ((u - 0.2) / 0.8)));
}

float param_at(const ParamInfo& p, double u) {
    if (p.type == "bool") return u < 0.5 ? p.min_value : p.max_value;
    const double v = p.min_value + (double(p.max_value) - p.min_value) * u;
    return p.type == "int" ? float(std::round(v)) : float(v);
}

}  // namespace

const std::vector<InputDimension>& input_dimensions() {
    static const std::vector<InputDimension> dimensions = {
        {"canvas", "the canvas width and height, and their parity"},
        {"floors", "how many floors the scene has"},
        {"plugin floor", "which floors carry the plugin (its floor index)"},
        {"pixels", "the input pixels: alpha 0, subnormal, ramps, 1; colour up to 65504"},
        {"floor names and tiles",
         "the floors' names (plain, 300 characters, beyond ASCII) and a floor without tiles"},
        {"lights",
         "the floor's lights (with heights): none, one, many, off the canvas, radius tiny "
         "and huge, on the floor at whole-pixel corners, colour and intensity 0; a sun at 40 "
         "degrees, on the horizon and overhead"},
        {"masks",
         "the floor's masks: absent, empty, full, partial, above 1, one-pixel lines, with "
         "content"},
        {"params", "the parameters: defaults, ends, presets, sweeps, combinations"},
        {"time", "acetate_time: 0, fractional, negative, large, a fraction that rounds up to 1"},
        {"frames", "frames rendered within one load before the one checked"},
        {"loads", "other scenes loaded and rendered in the process before this one"},
        {"poison", "what fills memory the plugin may read before writing it"},
        {"neighbours",
         "the effects before and after the plugin on its floor (or among the global effects): "
         "none, or the harness's coverage-expanding spread"},
        {"target format", "the format of the floors' targets and tiles: rgba16f or rgba32f"},
        {"camera",
         "what the host renders through (ABI 1.2): no camera, a region around the canvas at "
         "scale 1, or the whole canvas at scale 1/2 (each beside the case's own render)"},
    };
    return dimensions;
}

std::map<std::string, std::string> describe_inputs(const CaseSpec& s, const PluginInfo& plugin) {
    std::map<std::string, std::string> in = s.inputs;
    auto set = [&](const char* name, std::string value) { in.try_emplace(name, std::move(value)); };
    set("canvas",
        fmt::format("{}x{} ({} x {})", s.width, s.height, parity(s.width), parity(s.height)));
    set("floors", std::to_string(s.floors));
    set("plugin floor", plugin.is_global()   ? "the composite (global effect)"
                        : s.plugin_floor < 0 ? "every floor"
                                             : fmt::format("floor {} only", s.plugin_floor));
    set("pixels", to_string(s.pattern));
    set("lights", plugin.is_global() ? "none (global effect)" : to_string(s.lights));
    set("masks", plugin.masks.empty() ? "none read" : to_string(s.masks));
    set("floor names and tiles", to_string(s.floor_variant));
    set("params", !s.preset.empty() ? "preset " + s.preset : s.params.empty() ? "defaults" : "set");
    set("time", fmt::format("{:.9g} s", s.time));
    set("frames", std::to_string(s.frames));
    set("loads", std::to_string(s.prior_loads));
    set("poison", to_string(s.poison));
    std::string neighbours;
    for (const std::string& id : s.effects_before) neighbours += id + " before; ";
    for (const std::string& id : s.effects_after) neighbours += id + " after; ";
    set("neighbours", neighbours.empty() ? "none" : neighbours.substr(0, neighbours.size() - 2));
    set("target format", to_string(s.format));
    set("camera", s.relation == Relation::CameraRegion
                      ? "none, and a region starting 13 and 7 pixels left of and above the canvas"
                  : s.relation == Relation::CameraScale ? "none, and the whole canvas at scale 1/2"
                                                        : "none");
    return in;
}

std::vector<std::vector<double>> latin_hypercube(size_t points, size_t dimensions, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<std::vector<double>> out(points, std::vector<double>(dimensions));
    std::vector<size_t> strata(points);
    for (size_t d = 0; d < dimensions; ++d) {
        std::iota(strata.begin(), strata.end(), size_t(0));
        std::shuffle(strata.begin(), strata.end(), rng);
        for (size_t i = 0; i < points; ++i) out[i][d] = (double(strata[i]) + unit(rng)) / points;
    }
    return out;
}

size_t scenario_dimensions(const PluginInfo& plugin) {
    return 11 + plugin.params.size();
}

void scenario_at(const PluginInfo& plugin, std::span<const double> u, CaseSpec& s) {
    s.kind = CaseKind::Contract;
    s.width = log_size(u[0], 300);
    s.height = log_size(u[1], 200);
    s.floors = 1 + std::min(3u, uint32_t(u[2] * 4));
    // Half of the points put a floor effect on one floor only, whose index is drawn too.
    s.plugin_floor = plugin.is_global() || u[3] < 0.5
                         ? -1
                         : int32_t(std::min<double>(s.floors - 1, (u[3] - 0.5) * 2 * s.floors));
    s.pattern = category<Pattern>(u[4], 6);
    s.lights = category<LightSet>(u[5], kLightSetCount);
    s.masks = category<MaskFill>(u[6], kMaskFillCount);
    s.time = time_at(u[7]);
    s.frames = 1 + std::min(3u, uint32_t(u[8] * 4));
    s.prior_loads = std::min(2u, uint32_t(u[9] * 3));
    s.floor_variant = category<FloorVariant>(u[10], kFloorVariantCount);
    s.params = nlohmann::json::object();
    for (size_t i = 0; i < plugin.params.size(); ++i)
        s.params[plugin.params[i].name] = param_at(plugin.params[i], u[11 + i]);
}

std::vector<float> sweep_values(const ParamInfo& p, int points) {
    std::vector<float> values;
    if (p.type == "bool") return {p.min_value, p.max_value};
    points = std::max(points, 2);
    for (int i = 0; i < points; ++i) {
        const float v = param_at(p, double(i) / (points - 1));
        if (values.empty() || values.back() != v) values.push_back(v);
    }
    return values;
}

}  // namespace acetate::harness
