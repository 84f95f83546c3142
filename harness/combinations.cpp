#include "combinations.hpp"

#include <fmt/format.h>

#include <functional>

#include "neighbours.hpp"
#include "pairwise.hpp"

namespace acetate::harness {
namespace {

using nlohmann::json;

struct Canvas {
    uint32_t width, height;
};
// One pixel, odd by odd, even by even, everyday, one pixel high: the sizes' edges.
constexpr Canvas kCanvases[] = {{1, 1}, {37, 23}, {38, 24}, {128, 96}, {333, 1}};
// One, even, odd: five and eight floors are the own cases' (floors/top-of-five, floors/eight);
// here every floor multiplies the case's cost.
constexpr uint32_t kFloors[] = {1, 2, 3};
// 0, fractional, negative, large, a fraction that rounds up to 1 as a float.
constexpr double kTimes[] = {0.0, 0.37, -2.5, 1.0e5, 2.99999999};
constexpr uint32_t kFrames[] = {1, 3};
constexpr uint32_t kLoads[] = {0, 2};
enum class Neighbour { None, Before, After };
constexpr const char* kNeighbourNames[] = {"none", "spread before", "spread after"};
enum class ParamLevel { Min, Default, Max };
constexpr const char* kParamLevelNames[] = {"minimum", "default", "maximum"};

float param_value(const ParamInfo& p, ParamLevel level) {
    return level == ParamLevel::Min   ? p.min_value
           : level == ParamLevel::Max ? p.max_value
                                      : p.default_value;
}

// Every factor with what setting one of its levels does to a case.
struct Factor {
    CombinationFactor shown;
    std::function<void(int level, CaseSpec&)> apply;
};

std::vector<Factor> factors_of(const PluginInfo& plugin) {
    std::vector<Factor> out;
    auto names = [](auto first, auto last, auto name) {
        std::vector<std::string> levels;
        for (auto it = first; it != last; ++it) levels.push_back(name(*it));
        return levels;
    };
    out.push_back(
        {{"canvas", names(std::begin(kCanvases), std::end(kCanvases),
                          [](Canvas c) { return fmt::format("{}x{}", c.width, c.height); })},
         [](int l, CaseSpec& s) {
             s.width = kCanvases[l].width;
             s.height = kCanvases[l].height;
         }});
    out.push_back({{"floors", names(std::begin(kFloors), std::end(kFloors),
                                    [](uint32_t n) { return std::to_string(n); })},
                   [](int l, CaseSpec& s) { s.floors = kFloors[l]; }});
    if (!plugin.is_global())
        out.push_back({{"plugin floor", {"every floor", "the top floor only"}},
                       [](int l, CaseSpec& s) { s.plugin_floor = l == 0 ? -1 : -2; }});
    {
        std::vector<std::string> levels;
        for (int p = 0; p < 6; ++p) levels.push_back(to_string(Pattern(p)));
        out.push_back({{"pixels", levels}, [](int l, CaseSpec& s) { s.pattern = Pattern(l); }});
    }
    {
        std::vector<std::string> levels;
        for (int v = 0; v < kFloorVariantCount; ++v) levels.push_back(to_string(FloorVariant(v)));
        out.push_back({{"floor names and tiles", levels},
                       [](int l, CaseSpec& s) { s.floor_variant = FloorVariant(l); }});
    }
    if (!plugin.is_global()) {
        std::vector<std::string> levels;
        for (int v = 0; v < kLightSetCount; ++v) levels.push_back(to_string(LightSet(v)));
        out.push_back({{"lights", levels}, [](int l, CaseSpec& s) { s.lights = LightSet(l); }});
    }
    if (!plugin.masks.empty()) {
        std::vector<std::string> levels;
        for (int v = 0; v < kMaskFillCount; ++v) levels.push_back(to_string(MaskFill(v)));
        out.push_back({{"masks", levels}, [](int l, CaseSpec& s) { s.masks = MaskFill(l); }});
    }
    out.push_back({{"time", names(std::begin(kTimes), std::end(kTimes),
                                  [](double t) { return fmt::format("{:.9g} s", t); })},
                   [](int l, CaseSpec& s) { s.time = kTimes[l]; }});
    out.push_back({{"frames", names(std::begin(kFrames), std::end(kFrames),
                                    [](uint32_t n) { return std::to_string(n); })},
                   [](int l, CaseSpec& s) { s.frames = kFrames[l]; }});
    out.push_back({{"loads", names(std::begin(kLoads), std::end(kLoads),
                                   [](uint32_t n) { return std::to_string(n); })},
                   [](int l, CaseSpec& s) { s.prior_loads = kLoads[l]; }});
    const std::string spread = spread_neighbour_id(plugin.is_global());
    out.push_back({{"neighbours", {std::begin(kNeighbourNames), std::end(kNeighbourNames)}},
                   [spread](int l, CaseSpec& s) {
                       if (Neighbour(l) == Neighbour::Before) s.effects_before = {spread};
                       if (Neighbour(l) == Neighbour::After) s.effects_after = {spread};
                   }});
    out.push_back({{"target format", {"rgba16f", "rgba32f"}},
                   [](int l, CaseSpec& s) { s.format = TargetFormat(l); }});
    if (!plugin.presets.empty()) {
        std::vector<std::string> levels{"none"};
        levels.insert(levels.end(), plugin.presets.begin(), plugin.presets.end());
        out.push_back({{"preset", levels}, [presets = plugin.presets](int l, CaseSpec& s) {
                           s.preset = l == 0 ? std::string() : presets[size_t(l - 1)];
                       }});
    }
    // Each parameter (each component of a vector) at its minimum, default and maximum; a bool
    // at both. The scene's value overrides a preset's, so each also meets each preset.
    for (const ParamInfo& p : plugin.params) {
        const bool two = p.type == "bool";
        const std::vector<std::string> levels =
            two ? std::vector<std::string>{"false", "true"}
                : std::vector<std::string>(std::begin(kParamLevelNames),
                                           std::end(kParamLevelNames));
        for (uint32_t k = 0; k < p.components; ++k) {
            const std::string name =
                p.components > 1 ? fmt::format("params.{}[{}]", p.name, k) : "params." + p.name;
            out.push_back({{name, levels}, [p, k, two](int l, CaseSpec& s) {
                               const float v = two ? (l ? p.max_value : p.min_value)
                                                   : param_value(p, ParamLevel(l));
                               if (p.components == 1) {
                                   s.params[p.name] = v;
                                   return;
                               }
                               json& vector = s.params[p.name];
                               if (!vector.is_array())
                                   vector = json(std::vector<float>(p.components, p.default_value));
                               vector[k] = v;
                           }});
        }
    }
    return out;
}

}  // namespace

std::vector<CombinationFactor> combination_factors(const PluginInfo& plugin) {
    std::vector<CombinationFactor> out;
    for (Factor& f : factors_of(plugin)) out.push_back(std::move(f.shown));
    return out;
}

Combinations pairwise_combinations(const PluginInfo& plugin, uint64_t run_seed) {
    const std::vector<Factor> factors = factors_of(plugin);
    std::vector<int> levels;
    for (const Factor& f : factors) levels.push_back(int(f.shown.levels.size()));
    const CoveringArray design = pairwise_covering_array(levels, case_seed(run_seed, "pairwise"));
    Combinations out;
    out.summary = fmt::format(
        "pairwise (strength 2) over {} factors: all {} pairs of their values in {} cases",
        factors.size(), design.pairs, design.rows.size());
    for (size_t i = 0; i < design.rows.size(); ++i) {
        CaseSpec s;
        s.id = fmt::format("combined/pairwise-{}", i + 1);
        s.description = fmt::format("point {} of the pairwise design: {}", i + 1, out.summary);
        s.width = 128;
        s.height = 96;
        // The report shows the other dimensions from the case itself (describe_inputs); the
        // parameters and preset, which it can only call "set", are named here.
        std::string params;
        for (size_t f = 0; f < factors.size(); ++f) {
            const int level = design.rows[i][f];
            factors[f].apply(level, s);
            const std::string& name = factors[f].shown.name;
            if (name == "preset" || name.starts_with("params."))
                params += fmt::format("{}{} {}", params.empty() ? "" : ", ",
                                      name == "preset" ? name : name.substr(7),
                                      factors[f].shown.levels[size_t(level)]);
        }
        if (!params.empty()) s.inputs["params"] = "pairwise: " + params;
        // "The top floor only", once the floor count is known.
        if (s.plugin_floor == -2) s.plugin_floor = int32_t(s.floors) - 1;
        out.cases.push_back(std::move(s));
    }
    return out;
}

}  // namespace acetate::harness
