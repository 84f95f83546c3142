#include "case_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace acetate::harness {
namespace {

using nlohmann::json;

constexpr const char* kKindNames[] = {"contract",        "determinism",  "state-isolation",
                                      "floor-isolation", "disconnected", "integration"};
constexpr const char* kPatternNames[] = {"standard", "alpha-ramp", "hdr", "empty", "opaque"};

template <class Enum, size_t N>
std::optional<Enum> parse_enum(const char* const (&names)[N], const std::string& name) {
    for (size_t i = 0; i < N; ++i)
        if (name == names[i]) return Enum(i);
    return std::nullopt;
}

uint64_t splitmix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// A parameter value drawn uniformly from its range, as the host would resolve it.
float random_value(const ParamInfo& p, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double v = p.min_value + (double(p.max_value) - p.min_value) * unit(rng);
    if (p.type == "int") return float(std::round(v));
    if (p.type == "bool") return unit(rng) < 0.5 ? 0.0f : 1.0f;
    return float(v);
}

json all_params_at(const PluginInfo& plugin, bool at_max) {
    json params = json::object();
    for (const ParamInfo& p : plugin.params) params[p.name] = at_max ? p.max_value : p.min_value;
    return params;
}

}  // namespace

const char* to_string(CaseKind kind) {
    return kKindNames[int(kind)];
}
const char* to_string(Pattern pattern) {
    return kPatternNames[int(pattern)];
}

json to_json(const PluginInfo& info) {
    json params = json::array();
    for (const ParamInfo& p : info.params)
        params.push_back({{"name", p.name},
                          {"type", p.type},
                          {"default", p.default_value},
                          {"min", p.min_value},
                          {"max", p.max_value}});
    return {{"file", info.file},
            {"id", info.id},
            {"version", info.version},
            {"display_name", info.display_name},
            {"scope", info.scope},
            {"coverage", info.coverage},
            {"masks", info.masks},
            {"params", params},
            {"presets", info.presets},
            {"source_digest", info.source_digest},
            {"binary_sha256", info.binary_sha256}};
}

Result<PluginInfo> plugin_info_from_json(const json& j, std::string_view name) {
    try {
        PluginInfo info;
        info.file = j.at("file").get<std::string>();
        info.id = j.at("id").get<std::string>();
        info.version = j.at("version").get<std::string>();
        info.display_name = j.at("display_name").get<std::string>();
        info.scope = j.at("scope").get<std::string>();
        info.coverage = j.at("coverage").get<std::string>();
        info.masks = j.at("masks").get<std::vector<std::string>>();
        for (const json& p : j.at("params"))
            info.params.push_back({p.at("name").get<std::string>(), p.at("type").get<std::string>(),
                                   p.at("default").get<float>(), p.at("min").get<float>(),
                                   p.at("max").get<float>()});
        info.presets = j.at("presets").get<std::vector<std::string>>();
        info.source_digest = j.at("source_digest").get<std::string>();
        info.binary_sha256 = j.at("binary_sha256").get<std::string>();
        return info;
    } catch (const json::exception& e) {
        return make_error(ErrorCode::InvalidInput, fmt::format("{}: {}", name, e.what()));
    }
}

json to_json(const CaseSpec& s) {
    json companions = json::array();
    for (const CompanionPlugin& c : s.companions)
        companions.push_back({{"id", c.id}, {"file", c.file}, {"scope", c.scope}});
    return {{"id", s.id},
            {"description", s.description},
            {"kind", to_string(s.kind)},
            {"seed", s.seed},
            {"width", s.width},
            {"height", s.height},
            {"pattern", to_string(s.pattern)},
            {"floors", s.floors},
            {"params", s.params},
            {"preset", s.preset},
            {"time", s.time},
            {"switches", s.switches},
            {"companions", companions}};
}

Result<CaseSpec> case_spec_from_json(const json& j, std::string_view name) {
    try {
        CaseSpec s;
        s.id = j.at("id").get<std::string>();
        s.description = j.at("description").get<std::string>();
        const auto kind = parse_enum<CaseKind>(kKindNames, j.at("kind").get<std::string>());
        const auto pattern = parse_enum<Pattern>(kPatternNames, j.at("pattern").get<std::string>());
        if (!kind || !pattern)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: unknown case kind or pattern", name));
        s.kind = *kind;
        s.pattern = *pattern;
        s.seed = j.at("seed").get<uint64_t>();
        s.width = j.at("width").get<uint32_t>();
        s.height = j.at("height").get<uint32_t>();
        s.floors = j.at("floors").get<uint32_t>();
        s.params = j.at("params");
        s.preset = j.at("preset").get<std::string>();
        s.time = j.at("time").get<float>();
        s.switches = j.at("switches").get<uint32_t>();
        for (const json& c : j.at("companions"))
            s.companions.push_back({c.at("id").get<std::string>(), c.at("file").get<std::string>(),
                                    c.at("scope").get<std::string>()});
        if (s.width == 0 || s.height == 0 || s.floors == 0)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: width, height and floors must be > 0", name));
        return s;
    } catch (const json::exception& e) {
        return make_error(ErrorCode::InvalidInput, fmt::format("{}: {}", name, e.what()));
    }
}

uint64_t case_seed(uint64_t run_seed, const std::string& case_id) {
    uint64_t h = 1469598103934665603ull;  // FNV-1a of the id, then mixed with the run's seed
    for (unsigned char c : case_id) h = (h ^ c) * 1099511628211ull;
    return splitmix64(run_seed ^ splitmix64(h));
}

std::vector<CaseSpec> plan_cases(const PluginInfo& plugin, int strictness, uint64_t run_seed,
                                 bool alpha_stage, bool integration_stage,
                                 const std::vector<CompanionPlugin>& companions) {
    strictness = std::clamp(strictness, 1, 10);
    std::vector<CaseSpec> cases;
    auto add = [&](CaseSpec s) {
        s.seed = case_seed(run_seed, s.id);
        cases.push_back(std::move(s));
    };
    auto contract = [&](std::string id, std::string description, uint32_t w, uint32_t h,
                        Pattern pattern = Pattern::Standard, uint32_t floors = 1) {
        CaseSpec s;
        s.id = std::move(id);
        s.description = std::move(description);
        s.width = w;
        s.height = h;
        s.pattern = pattern;
        s.floors = floors;
        return s;
    };

    if (alpha_stage) {
        add(contract("contract/standard", "one floor: opaque, partial and transparent areas", 256,
                     160));
        add(contract("contract/three-floors",
                     "three overlapping floors, each with its own coverage and lights", 256, 160,
                     Pattern::Standard, 3));
        add(contract("sizes/1x1", "a 1x1 canvas", 1, 1));
        add(contract("sizes/odd", "an odd size, 37x23", 37, 23));
        add(contract("sizes/thin", "a one-pixel-high strip, 333x1", 333, 1));
        if (strictness >= 7) add(contract("sizes/tall", "a one-pixel-wide strip, 1x517", 1, 517));
        const uint32_t large_w = strictness <= 3 ? 1024 : strictness <= 7 ? 1920 : 4096;
        const uint32_t large_h = strictness <= 3 ? 768 : strictness <= 7 ? 1080 : 2304;
        add(contract(fmt::format("sizes/large"),
                     fmt::format("a large canvas, {}x{}", large_w, large_h), large_w, large_h));
        add(contract("inputs/hdr", "HDR values up to the half-float maximum 65504", 128, 96,
                     Pattern::Hdr));
        add(contract("inputs/alpha-ramp", "alpha from 1 down to 1/65535 across the canvas", 256, 64,
                     Pattern::AlphaRamp));
        add(contract("inputs/empty", "a floor whose tile is fully transparent", 96, 64,
                     Pattern::Empty));
        add(contract("inputs/opaque", "a floor that is opaque everywhere", 96, 64,
                     Pattern::Opaque));

        if (!plugin.params.empty()) {
            CaseSpec s = contract("params/min", "every parameter at its minimum", 128, 96);
            s.params = all_params_at(plugin, false);
            add(s);
            s = contract("params/max", "every parameter at its maximum", 128, 96);
            s.params = all_params_at(plugin, true);
            add(s);
        }
        for (const std::string& preset : plugin.presets) {
            CaseSpec s = contract("params/preset-" + preset, "preset \"" + preset + "\"", 128, 96);
            s.preset = preset;
            add(s);
        }
        const int random_cases = plugin.params.empty() ? 0 : std::max(1, strictness);
        for (int i = 0; i < random_cases; ++i) {
            CaseSpec s =
                contract(fmt::format("params/random-{}", i + 1),
                         "random parameters within their ranges, at a random time", 128, 96);
            s.seed = case_seed(run_seed, s.id);
            std::mt19937_64 rng(s.seed);
            for (const ParamInfo& p : plugin.params) s.params[p.name] = random_value(p, rng);
            s.time = float(std::uniform_real_distribution<double>(0.0, 10.0)(rng));
            cases.push_back(s);  // seed already set: the parameters were drawn from it
        }

        for (int run = 1; run <= 2; ++run) {
            CaseSpec s = contract(fmt::format("determinism/run-{}", run),
                                  "the same case in two processes, two frames each", 192, 128,
                                  Pattern::Standard, 2);
            s.kind = CaseKind::Determinism;
            s.seed = case_seed(run_seed, "determinism");  // both runs: the same inputs
            cases.push_back(s);
        }
        CaseSpec state = contract("isolation/state",
                                  "floors 0, 1, 0; each floor alone; a second load; then many "
                                  "switches for memory growth",
                                  160, 96, Pattern::Standard, 2);
        state.kind = CaseKind::StateIsolation;
        state.switches = uint32_t(20 * strictness);
        add(state);
        if (!plugin.is_global()) {
            CaseSpec floor = contract("isolation/floors",
                                      "the composite with and without the effect on floor 1 of 3",
                                      192, 128, Pattern::Standard, 3);
            floor.kind = CaseKind::FloorIsolation;
            add(floor);
        }
        if (!plugin.params.empty()) {
            CaseSpec s = contract("params/disconnected",
                                  "each parameter at its minimum and maximum must change the "
                                  "output (lights, masks and three times given)",
                                  128, 96);
            s.kind = CaseKind::Disconnected;
            add(s);
        }
    }

    if (integration_stage) {
        CaseSpec s = contract("integration/stack",
                              "four floors with the other integrated plugins, against the "
                              "composite rebuilt from each floor rendered alone",
                              256, 160, Pattern::Standard, 4);
        s.kind = CaseKind::Integration;
        s.companions = companions;
        add(s);
        if (strictness >= 5) {
            s = contract("integration/stack-hdr",
                         "the same stack on HDR inputs near the half-float maximum", 128, 96,
                         Pattern::Hdr, 4);
            s.kind = CaseKind::Integration;
            s.companions = companions;
            add(s);
        }
    }
    return cases;
}

}  // namespace acetate::harness
