#include "case_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace acetate::harness {
namespace {

using nlohmann::json;

constexpr const char* kKindNames[] = {"contract",        "determinism",  "state-isolation",
                                      "floor-isolation", "disconnected", "integration",
                                      "undefined",       "golden"};
constexpr const char* kPatternNames[] = {"standard", "alpha-ramp", "hdr",
                                         "empty",    "opaque",     "subnormal"};
constexpr const char* kLightNames[] = {"three",       "none",       "one",
                                       "many",        "off-canvas", "tiny-radius",
                                       "huge-radius", "sun",        "grazing-sun"};
constexpr const char* kMaskNames[] = {"content", "absent", "empty", "full", "partial"};
constexpr const char* kPoisonNames[] = {"none", "nan", "large", "plain"};

template <class Enum, size_t N>
std::optional<Enum> parse_enum(const char* const (&names)[N], const std::string& name) {
    for (size_t i = 0; i < N; ++i)
        if (name == names[i]) return Enum(i);
    return std::nullopt;
}

}  // namespace

const char* to_string(CaseKind kind) {
    return kKindNames[int(kind)];
}
const char* to_string(Pattern pattern) {
    return kPatternNames[int(pattern)];
}
const char* to_string(LightSet lights) {
    return kLightNames[int(lights)];
}
const char* to_string(MaskFill masks) {
    return kMaskNames[int(masks)];
}
const char* to_string(Poison poison) {
    return kPoisonNames[int(poison)];
}

json to_json(const PluginInfo& info) {
    json params = json::array();
    for (const ParamInfo& p : info.params)
        params.push_back({{"name", p.name},
                          {"type", p.type},
                          {"default", p.default_value},
                          {"min", p.min_value},
                          {"max", p.max_value},
                          {"components", p.components}});
    json scenes = json::array();
    for (const ReferenceScene& r : info.reference_scenes)
        scenes.push_back({{"name", r.name},
                          {"file", r.file},
                          {"digest", r.digest},
                          {"width", r.width},
                          {"height", r.height}});
    return {{"file", info.file},
            {"id", info.id},
            {"version", info.version},
            {"display_name", info.display_name},
            {"scope", info.scope},
            {"coverage", info.coverage},
            {"masks", info.masks},
            {"params", params},
            {"hidden_params", info.hidden_params},
            {"presets", info.presets},
            {"abi", info.abi},
            {"source_digest", info.source_digest},
            {"binary_sha256", info.binary_sha256},
            {"reference_scenes", scenes}};
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
                                   p.at("max").get<float>(), p.at("components").get<uint32_t>()});
        info.hidden_params = j.at("hidden_params").get<std::vector<std::string>>();
        info.abi = j.at("abi").get<std::string>();
        info.presets = j.at("presets").get<std::vector<std::string>>();
        info.source_digest = j.at("source_digest").get<std::string>();
        info.binary_sha256 = j.at("binary_sha256").get<std::string>();
        for (const json& r : j.value("reference_scenes", json::array()))
            info.reference_scenes.push_back(
                {r.at("name").get<std::string>(), r.at("file").get<std::string>(),
                 r.at("digest").get<std::string>(), r.at("width").get<uint32_t>(),
                 r.at("height").get<uint32_t>()});
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
            {"companions", companions},
            {"lights", to_string(s.lights)},
            {"masks", to_string(s.masks)},
            {"plugin_floor", s.plugin_floor},
            {"frames", s.frames},
            {"prior_loads", s.prior_loads},
            {"sweep", s.sweep},
            {"poison", to_string(s.poison)},
            {"inputs", s.inputs},
            {"reference", s.reference},
            {"scene_file", s.scene_file}};
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
        const auto lights = parse_enum<LightSet>(kLightNames, j.at("lights").get<std::string>());
        const auto masks = parse_enum<MaskFill>(kMaskNames, j.at("masks").get<std::string>());
        const auto poison = parse_enum<Poison>(kPoisonNames, j.at("poison").get<std::string>());
        if (!lights || !masks || !poison)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: unknown lights, masks or poison", name));
        s.kind = *kind;
        s.pattern = *pattern;
        s.lights = *lights;
        s.masks = *masks;
        s.poison = *poison;
        s.plugin_floor = j.at("plugin_floor").get<int32_t>();
        s.frames = j.at("frames").get<uint32_t>();
        s.prior_loads = j.at("prior_loads").get<uint32_t>();
        s.sweep = j.at("sweep").get<std::vector<json>>();
        s.inputs = j.at("inputs").get<std::map<std::string, std::string>>();
        s.seed = j.at("seed").get<uint64_t>();
        s.width = j.at("width").get<uint32_t>();
        s.height = j.at("height").get<uint32_t>();
        s.floors = j.at("floors").get<uint32_t>();
        s.params = j.at("params");
        s.preset = j.at("preset").get<std::string>();
        s.time = j.at("time").get<float>();
        s.switches = j.at("switches").get<uint32_t>();
        s.reference = j.value("reference", json());
        s.scene_file = j.value("scene_file", std::string());
        for (const json& c : j.at("companions"))
            s.companions.push_back({c.at("id").get<std::string>(), c.at("file").get<std::string>(),
                                    c.at("scope").get<std::string>()});
        if (s.width == 0 || s.height == 0 || s.floors == 0 || s.frames == 0)
            return make_error(
                ErrorCode::InvalidInput,
                fmt::format("{}: width, height, floors and frames must be > 0", name));
        if (s.plugin_floor >= int32_t(s.floors))
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: plugin_floor {} is not one of the {} floors", name,
                                          s.plugin_floor, s.floors));
        return s;
    } catch (const json::exception& e) {
        return make_error(ErrorCode::InvalidInput, fmt::format("{}: {}", name, e.what()));
    }
}

uint64_t splitmix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

uint64_t case_seed(uint64_t run_seed, const std::string& case_id) {
    uint64_t h = 1469598103934665603ull;  // FNV-1a of the id, then mixed with the run's seed
    for (unsigned char c : case_id) h = (h ^ c) * 1099511628211ull;
    return splitmix64(run_seed ^ splitmix64(h));
}

}  // namespace acetate::harness
