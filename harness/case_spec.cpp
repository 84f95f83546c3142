#include "case_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>

#include "case_kinds.hpp"
#include "core/json_fields.hpp"
#include "plugins/effect_descriptor.hpp"

namespace acetate::harness {
namespace {

using nlohmann::json;

constexpr const char* kPatternNames[] = {"standard", "alpha-ramp", "hdr",
                                         "empty",    "opaque",     "subnormal"};
constexpr const char* kLightNames[] = {"three",       "none",        "one",          "many",
                                       "off-canvas",  "tiny-radius", "huge-radius",  "sun",
                                       "grazing-sun", "zenith-sun",  "on-the-floor", "dark"};
static_assert(std::size(kLightNames) == kLightSetCount);
constexpr const char* kMaskNames[] = {"content", "absent",    "empty", "full",
                                      "partial", "above-one", "thin"};
static_assert(std::size(kMaskNames) == kMaskFillCount);
constexpr const char* kFloorVariantNames[] = {"standard", "long-names", "unicode-names",
                                              "top-floor-empty"};
static_assert(std::size(kFloorVariantNames) == kFloorVariantCount);
constexpr const char* kPoisonNames[] = {"none", "nan", "large", "plain"};
constexpr const char* kFormatNames[] = {"rgba16f", "rgba32f"};
constexpr const char* kRelationNames[] = {"none", "canvas-size", "format-agreement",
                                          "camera-region", "camera-scale"};

template <class Enum, size_t N>
std::optional<Enum> parse_enum(const char* const (&names)[N], const std::string& name) {
    for (size_t i = 0; i < N; ++i)
        if (name == names[i]) return Enum(i);
    return std::nullopt;
}

}  // namespace

const char* to_string(Pattern pattern) {
    return kPatternNames[int(pattern)];
}
const char* to_string(LightSet lights) {
    return kLightNames[int(lights)];
}
const char* to_string(FloorVariant floors) {
    return kFloorVariantNames[int(floors)];
}
const char* to_string(MaskFill masks) {
    return kMaskNames[int(masks)];
}
const char* to_string(Poison poison) {
    return kPoisonNames[int(poison)];
}
const char* to_string(TargetFormat format) {
    return kFormatNames[int(format)];
}
const char* to_string(Relation relation) {
    return kRelationNames[int(relation)];
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
            {"scale_tolerance", info.scale_tolerance},
            {"source_digest", info.source_digest},
            {"binary_sha256", info.binary_sha256},
            {"reference_scenes", scenes}};
}

PluginInfo read_plugin_info(const json& j, const std::string& path) {
    using namespace json_fields;
    expect_object(j, path,
                  {"file", "id", "version", "display_name", "scope", "coverage", "masks", "params",
                   "hidden_params", "abi", "presets", "source_digest", "binary_sha256"},
                  {"reference_scenes", "scale_tolerance"});
    PluginInfo info;
    info.file = text(j, path, "file");
    info.id = text(j, path, "id");
    info.version = text(j, path, "version");
    info.display_name = text(j, path, "display_name");
    info.scope = text(j, path, "scope");
    info.coverage = text(j, path, "coverage");
    info.masks = texts(j, path, "masks");
    const std::string params_path = field(path, "params");
    const json& params = array(j.at("params"), params_path);
    for (size_t i = 0; i < params.size(); ++i) {
        const json& p = params[i];
        const std::string at = element(params_path, i);
        expect_object(p, at, {"name", "type", "default", "min", "max", "components"});
        info.params.push_back({text(p, at, "name"), text(p, at, "type"),
                               finite_float(p, at, "default"), finite_float(p, at, "min"),
                               finite_float(p, at, "max"),
                               uint32_t(unsigned_integer(p, at, "components", 4))});
    }
    info.hidden_params = texts(j, path, "hidden_params");
    info.abi = text(j, path, "abi");
    if (optional(j, "scale_tolerance")) {
        info.scale_tolerance = finite_float(j, path, "scale_tolerance");
        if (!(info.scale_tolerance >= 0 && info.scale_tolerance <= kMaxScaleTolerance))
            fail(field(path, "scale_tolerance"),
                 fmt::format("{} is not from 0 to {}", info.scale_tolerance, kMaxScaleTolerance));
    }
    info.presets = texts(j, path, "presets");
    info.source_digest = text(j, path, "source_digest");
    info.binary_sha256 = text(j, path, "binary_sha256");
    if (const json* scenes = optional(j, "reference_scenes")) {
        const std::string scenes_path = field(path, "reference_scenes");
        array(*scenes, scenes_path);
        for (size_t i = 0; i < scenes->size(); ++i) {
            const json& r = (*scenes)[i];
            const std::string at = element(scenes_path, i);
            expect_object(r, at, {"name", "file", "digest", "width", "height"});
            info.reference_scenes.push_back(
                {text(r, at, "name"), text(r, at, "file"), text(r, at, "digest"),
                 uint32_t(unsigned_integer(r, at, "width", UINT32_MAX)),
                 uint32_t(unsigned_integer(r, at, "height", UINT32_MAX))});
        }
    }
    return info;
}

Result<PluginInfo> plugin_info_from_json(const json& j, std::string_view name) {
    return json_fields::read_json(name, [&] { return read_plugin_info(j, ""); });
}

json to_json(const CaseSpec& s) {
    json companions = json::array();
    for (const CompanionPlugin& c : s.companions)
        companions.push_back({{"id", c.id},
                              {"file", c.file},
                              {"scope", c.scope},
                              {"binary_sha256", c.binary_sha256}});
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
            {"effects_before", s.effects_before},
            {"effects_after", s.effects_after},
            {"format", to_string(s.format)},
            {"relation", to_string(s.relation)},
            {"lights", to_string(s.lights)},
            {"masks", to_string(s.masks)},
            {"floor_variant", to_string(s.floor_variant)},
            {"plugin_floor", s.plugin_floor},
            {"frames", s.frames},
            {"prior_loads", s.prior_loads},
            {"validation_layer", s.validation_layer},
            {"sweep", s.sweep},
            {"poison", to_string(s.poison)},
            {"inputs", s.inputs},
            {"reference", s.reference},
            {"scene_file", s.scene_file}};
}

namespace {

// One of `names`, as the enum it indexes.
template <class Enum, size_t N>
Enum enum_field(const json& j, const std::string& path, std::string_view key,
                const char* const (&names)[N]) {
    const std::string name = json_fields::text(j, path, key);
    if (const auto value = parse_enum<Enum>(names, name)) return *value;
    std::string known;
    for (const char* n : names) known += (known.empty() ? "" : ", ") + std::string(n);
    json_fields::fail(
        json_fields::field(path, key),
        fmt::format("unknown value {} (known: {})", json_fields::json_quoted(name), known));
}

// The kind a case names, one of the registered ones (case_kinds.hpp).
CaseKind case_kind_field(const json& j, const std::string& path) {
    const std::string name = json_fields::text(j, path, "kind");
    if (const CaseKindInfo* kind = find_case_kind(name)) return kind->kind;
    std::string known;
    for (const CaseKindInfo& k : registered_case_kinds())
        known += (known.empty() ? "" : ", ") + std::string(k.name);
    json_fields::fail(
        json_fields::field(path, "kind"),
        fmt::format("unknown value {} (known: {})", json_fields::json_quoted(name), known));
}

}  // namespace

CaseSpec read_case_spec(const json& j, const std::string& path) {
    using namespace json_fields;
    expect_object(j, path,
                  {"id",         "description", "kind",   "seed",         "width",  "height",
                   "pattern",    "floors",      "params", "preset",       "time",   "switches",
                   "companions", "lights",      "masks",  "plugin_floor", "frames", "prior_loads",
                   "sweep",      "poison",      "inputs", "floor_variant"},
                  {"reference", "scene_file", "effects_before", "effects_after", "format",
                   "relation", "validation_layer"});
    CaseSpec s;
    s.id = text(j, path, "id");
    s.description = text(j, path, "description");
    s.kind = case_kind_field(j, path);
    s.pattern = enum_field<Pattern>(j, path, "pattern", kPatternNames);
    s.lights = enum_field<LightSet>(j, path, "lights", kLightNames);
    s.masks = enum_field<MaskFill>(j, path, "masks", kMaskNames);
    s.floor_variant = enum_field<FloorVariant>(j, path, "floor_variant", kFloorVariantNames);
    s.poison = enum_field<Poison>(j, path, "poison", kPoisonNames);
    if (optional(j, "format")) s.format = enum_field<TargetFormat>(j, path, "format", kFormatNames);
    if (optional(j, "relation"))
        s.relation = enum_field<Relation>(j, path, "relation", kRelationNames);
    if (optional(j, "effects_before")) s.effects_before = texts(j, path, "effects_before");
    if (optional(j, "effects_after")) s.effects_after = texts(j, path, "effects_after");
    const int64_t plugin_floor = integer(j, path, "plugin_floor");
    if (plugin_floor < INT32_MIN || plugin_floor > INT32_MAX)
        fail(field(path, "plugin_floor"), fmt::format("is out of range, got {}", plugin_floor));
    s.plugin_floor = int32_t(plugin_floor);
    s.frames = uint32_t(unsigned_integer(j, path, "frames", UINT32_MAX));
    s.prior_loads = uint32_t(unsigned_integer(j, path, "prior_loads", UINT32_MAX));
    if (const json* layer = optional(j, "validation_layer"))
        s.validation_layer = boolean(*layer, field(path, "validation_layer"));
    s.sweep = array(j.at("sweep"), field(path, "sweep")).get<std::vector<json>>();
    const std::string inputs_path = field(path, "inputs");
    const json& inputs = j.at("inputs");
    if (!inputs.is_object()) fail(inputs_path, "must be an object, got " + describe(inputs));
    for (const auto& [key, value] : inputs.items())
        s.inputs[key] = text(value, field(inputs_path, key));
    s.seed = unsigned_integer(j, path, "seed");
    s.width = uint32_t(unsigned_integer(j, path, "width", UINT32_MAX));
    s.height = uint32_t(unsigned_integer(j, path, "height", UINT32_MAX));
    s.floors = uint32_t(unsigned_integer(j, path, "floors", UINT32_MAX));
    s.params = j.at("params");
    s.preset = text(j, path, "preset");
    s.time = finite_number(j.at("time"), field(path, "time"));
    s.switches = uint32_t(unsigned_integer(j, path, "switches", UINT32_MAX));
    s.reference = j.value("reference", json());
    if (const json* scene_file = optional(j, "scene_file"))
        s.scene_file = text(*scene_file, field(path, "scene_file"));
    const std::string companions_path = field(path, "companions");
    const json& companions = array(j.at("companions"), companions_path);
    for (size_t i = 0; i < companions.size(); ++i) {
        const json& c = companions[i];
        const std::string at = element(companions_path, i);
        expect_object(c, at, {"id", "file", "scope", "binary_sha256"});
        s.companions.push_back({text(c, at, "id"), text(c, at, "file"), text(c, at, "scope"),
                                text(c, at, "binary_sha256")});
    }
    if (s.width == 0 || s.height == 0 || s.floors == 0 || s.frames == 0)
        fail(path, "width, height, floors and frames must be > 0");
    if (s.plugin_floor >= int32_t(s.floors))
        fail(field(path, "plugin_floor"),
             fmt::format("{} is not one of the {} floors", s.plugin_floor, s.floors));
    return s;
}

Result<CaseSpec> case_spec_from_json(const json& j, std::string_view name) {
    return json_fields::read_json(name, [&] { return read_case_spec(j, ""); });
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
