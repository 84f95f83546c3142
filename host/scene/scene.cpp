#include "scene/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string_view>

#include "core/input_file.hpp"
#include "core/strict_json.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr std::string_view kFormat = "acetate-scene/1";
// Far above any real device limit; the renderer checks the device's own limit later.
constexpr int64_t kMaxCanvasSide = 65536;
// Effects consider a few dozen lights per floor (lighting's ultra preset: 64); 4096 leaves room
// for any real scene while a hostile one is refused before 100,000 lights cost seconds of load.
constexpr size_t kMaxLightsPerFloor = 4096;

// Thrown by the checks below and caught in parse_scene_text. Validation then reads top to
// bottom like the format it checks, and the first problem ends it. Never leaves this file.
struct ParseFailure {
    Error error;
};

std::string field_path(const std::string& parent, std::string_view key) {
    return parent.empty() ? std::string(key) : fmt::format("{}.{}", parent, key);
}

std::string item_path(const std::string& parent, size_t index) {
    return fmt::format("{}[{}]", parent, index);
}

// A short, single-line rendering of a value for "got ..." in messages.
std::string describe(const json& value) {
    if (value.is_structured()) return std::string(value.type_name());
    return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string json_quoted(std::string_view text) {
    return json(std::string(text)).dump(-1, ' ', false, json::error_handler_t::replace);
}

class SceneReader {
  public:
    SceneReader(std::string label, fs::path base_dir)
        : label_(std::move(label)), base_dir_(std::move(base_dir)) {}

    SceneDesc read(const json& root, const fs::path& file);

  private:
    [[noreturn]] void fail(const std::string& path, const std::string& what,
                           ErrorCode code = ErrorCode::InvalidInput) const {
        const std::string message = path.empty() ? fmt::format("{}: {}", label_, what)
                                                 : fmt::format("{}: {}: {}", label_, path, what);
        throw ParseFailure{make_error(code, message)};
    }

    void expect_object(const json& value, const std::string& path,
                       std::initializer_list<std::string_view> allowed) const;
    const json& required(const json& object, const std::string& path, std::string_view key) const;
    const json* optional(const json& object, std::string_view key) const;
    const json& array_of(const json& value, const std::string& path, size_t count,
                         std::string_view shape) const;
    double finite_number(const json& value, const std::string& path) const;
    float finite_float(const json& value, const std::string& path) const;
    float float_at_least(const json& value, const std::string& path, float min, bool inclusive,
                         std::string_view what = "") const;
    int64_t integer(const json& value, const std::string& path) const;
    std::string non_empty_string(const json& value, const std::string& path) const;
    fs::path existing_file(const json& value, const std::string& path) const;

    void read_canvas(const json& canvas, const std::string& path, SceneDesc& scene) const;
    uint32_t canvas_side(const json& value, const std::string& path) const;
    std::array<float, 4> read_background(const json& value, const std::string& path) const;
    FloorDesc read_floor(const json& floor, const std::string& path) const;
    TileDesc read_tile(const json& tile, const std::string& path) const;
    SceneRect read_rect(const json& rect, const std::string& path) const;
    std::map<std::string, fs::path> read_masks(const json& masks, const std::string& path) const;
    LightDesc read_light(const json& light, const std::string& path) const;
    SunDesc read_sun(const json& sun, const std::string& path) const;
    std::array<float, 3> read_color(const json& color, const std::string& path) const;
    std::vector<EffectRef> read_effects(const json* list, const std::string& path) const;
    EffectRef read_effect(const json& effect, const std::string& path) const;
    void check_format(const json& root) const;
    uint32_t read_active_floor(const json* value, size_t floor_count) const;

    std::string label_;
    fs::path base_dir_;
};

// Type check plus "unknown field": a misspelt optional field must not be silently ignored.
void SceneReader::expect_object(const json& value, const std::string& path,
                                std::initializer_list<std::string_view> allowed) const {
    if (!value.is_object()) fail(path, "must be an object, got " + describe(value));
    for (const auto& [key, unused] : value.items()) {
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        std::string names;
        for (std::string_view name : allowed)
            names += (names.empty() ? "" : ", ") + std::string(name);
        fail(path, fmt::format("unknown field {} (allowed: {})", json_quoted(key), names));
    }
}

const json& SceneReader::required(const json& object, const std::string& path,
                                  std::string_view key) const {
    const json* value = optional(object, key);
    if (!value) fail(path, fmt::format("missing required field {}", json_quoted(key)));
    return *value;
}

const json* SceneReader::optional(const json& object, std::string_view key) const {
    const auto it = object.find(std::string(key));
    return it == object.end() ? nullptr : &*it;
}

const json& SceneReader::array_of(const json& value, const std::string& path, size_t count,
                                  std::string_view shape) const {
    if (!value.is_array())
        fail(path, fmt::format("must be an array of {}, got {}", shape, describe(value)));
    if (value.size() != count)
        fail(path, fmt::format("must be an array of {}, got {} elements", shape, value.size()));
    return value;
}

double SceneReader::finite_number(const json& value, const std::string& path) const {
    if (!value.is_number()) fail(path, "must be a number, got " + describe(value));
    const double number = value.get<double>();
    // The parser already refuses overflowing literals (1e999); this keeps the promise local.
    if (!std::isfinite(number)) fail(path, "must be a finite number, got " + describe(value));
    return number;
}

float SceneReader::finite_float(const json& value, const std::string& path) const {
    const double number = finite_number(value, path);
    if (std::abs(number) > double(std::numeric_limits<float>::max()))
        fail(path, "is out of range for a 32-bit float, got " + describe(value));
    return float(number);
}

float SceneReader::float_at_least(const json& value, const std::string& path, float min,
                                  bool inclusive, std::string_view what) const {
    const float number = finite_float(value, path);
    if (inclusive ? number >= min : number > min) return number;
    const std::string subject = what.empty() ? "must be" : fmt::format("{} must be", what);
    fail(path,
         fmt::format("{} {} {}, got {}", subject, inclusive ? ">=" : ">", min, describe(value)));
}

int64_t SceneReader::integer(const json& value, const std::string& path) const {
    if (!value.is_number_integer()) fail(path, "must be an integer, got " + describe(value));
    if (value.is_number_unsigned() && value.get<uint64_t>() > uint64_t(INT64_MAX))
        fail(path, "is out of range, got " + describe(value));
    return value.get<int64_t>();
}

std::string SceneReader::non_empty_string(const json& value, const std::string& path) const {
    if (!value.is_string()) fail(path, "must be a string, got " + describe(value));
    std::string text = value.get<std::string>();
    if (text.empty()) fail(path, "must not be empty");
    return text;
}

// Paths are relative to the scene file; existence is checked now so that a typo is reported
// with its JSON path instead of surfacing later as a decode failure.
fs::path SceneReader::existing_file(const json& value, const std::string& path) const {
    const std::string text = non_empty_string(value, path);
    if (text.find('\0') != std::string::npos) fail(path, "path contains a NUL character");
    const fs::path resolved = (base_dir_ / fs::path(text)).lexically_normal();
    std::error_code ec;
    const fs::file_status status = fs::status(resolved, ec);
    // status() says "not found" for ENOENT and ENOTDIR; any other failure (a name longer than
    // PATH_MAX, a folder it may not search) is not a missing file and is reported as itself.
    if (status.type() == fs::file_type::none)
        fail(path, fmt::format("cannot check {}: {}", resolved.string(), ec.message()),
             ErrorCode::Io);
    if (!fs::exists(status))
        fail(path, "file not found: " + resolved.string(), ErrorCode::FileNotFound);
    if (!fs::is_regular_file(status)) fail(path, "not a regular file: " + resolved.string());
    return resolved;
}

void SceneReader::check_format(const json& root) const {
    const json& format = required(root, "", "format");
    if (!format.is_string() || format.get<std::string>() != kFormat)
        fail("format", fmt::format("unsupported format {} (supported: {})", describe(format),
                                   json_quoted(kFormat)));
}

SceneDesc SceneReader::read(const json& root, const fs::path& file) {
    if (!root.is_object()) fail("", "the scene must be a JSON object, got " + describe(root));
    // The format decides which fields exist, so it is checked before any of them.
    check_format(root);
    expect_object(root, "", {"format", "canvas", "floors", "global_effects", "active_floor"});

    SceneDesc scene;
    scene.file = file;
    read_canvas(required(root, "", "canvas"), "canvas", scene);

    const json& floors = required(root, "", "floors");
    if (!floors.is_array()) fail("floors", "must be an array, got " + describe(floors));
    if (floors.empty()) fail("floors", "at least one floor is required");
    std::map<std::string, size_t> first_index_of_name;
    for (size_t i = 0; i < floors.size(); ++i) {
        const std::string path = item_path("floors", i);
        scene.floors.push_back(read_floor(floors[i], path));
        const auto [it, inserted] = first_index_of_name.emplace(scene.floors.back().name, i);
        if (!inserted)
            fail(field_path(path, "name"),
                 fmt::format("duplicate floor name {} (also floors[{}].name)",
                             json_quoted(scene.floors.back().name), it->second));
    }
    scene.global_effects = read_effects(optional(root, "global_effects"), "global_effects");
    scene.active_floor = read_active_floor(optional(root, "active_floor"), floors.size());
    return scene;
}

void SceneReader::read_canvas(const json& canvas, const std::string& path, SceneDesc& scene) const {
    expect_object(canvas, path, {"width", "height", "background"});
    scene.width = canvas_side(required(canvas, path, "width"), field_path(path, "width"));
    scene.height = canvas_side(required(canvas, path, "height"), field_path(path, "height"));
    if (const json* background = optional(canvas, "background"))
        scene.background = read_background(*background, field_path(path, "background"));
}

uint32_t SceneReader::canvas_side(const json& value, const std::string& path) const {
    if (!value.is_number_integer())
        fail(path, "must be a positive integer, got " + describe(value));
    if (value.is_number_unsigned() ? value.get<uint64_t>() > uint64_t(kMaxCanvasSide)
                                   : value.get<int64_t>() > kMaxCanvasSide)
        fail(path, fmt::format("must be <= {}, got {}", kMaxCanvasSide, describe(value)));
    const int64_t side = value.get<int64_t>();
    if (side <= 0) fail(path, "must be > 0, got " + describe(value));
    return uint32_t(side);
}

std::array<float, 4> SceneReader::read_background(const json& value,
                                                  const std::string& path) const {
    array_of(value, path, 4, "4 numbers [r, g, b, a]");
    std::array<float, 4> rgba{};
    for (size_t c = 0; c < 3; ++c)
        rgba[c] = float_at_least(value[c], item_path(path, c), 0.0f, true);
    rgba[3] = finite_float(value[3], item_path(path, 3));
    if (rgba[3] < 0.0f || rgba[3] > 1.0f)
        fail(item_path(path, 3), "alpha must be in [0, 1], got " + describe(value[3]));
    return rgba;
}

FloorDesc SceneReader::read_floor(const json& floor, const std::string& path) const {
    expect_object(floor, path, {"name", "tiles", "lights", "sun", "effects"});
    FloorDesc desc;
    desc.name = non_empty_string(required(floor, path, "name"), field_path(path, "name"));

    const std::string tiles_path = field_path(path, "tiles");
    const json& tiles = required(floor, path, "tiles");
    if (!tiles.is_array()) fail(tiles_path, "must be an array, got " + describe(tiles));
    for (size_t i = 0; i < tiles.size(); ++i)
        desc.tiles.push_back(read_tile(tiles[i], item_path(tiles_path, i)));

    if (const json* lights = optional(floor, "lights")) {
        const std::string lights_path = field_path(path, "lights");
        if (!lights->is_array()) fail(lights_path, "must be an array, got " + describe(*lights));
        if (lights->size() > kMaxLightsPerFloor)
            fail(lights_path, fmt::format("{} lights is over the limit of {} per floor",
                                          lights->size(), kMaxLightsPerFloor));
        for (size_t i = 0; i < lights->size(); ++i)
            desc.lights.push_back(read_light((*lights)[i], item_path(lights_path, i)));
    }
    if (const json* sun = optional(floor, "sun"))
        desc.sun = read_sun(*sun, field_path(path, "sun"));
    desc.effects = read_effects(optional(floor, "effects"), field_path(path, "effects"));
    return desc;
}

TileDesc SceneReader::read_tile(const json& tile, const std::string& path) const {
    expect_object(tile, path, {"image", "rect", "masks"});
    TileDesc desc;
    desc.image = existing_file(required(tile, path, "image"), field_path(path, "image"));
    desc.rect = read_rect(required(tile, path, "rect"), field_path(path, "rect"));
    if (const json* masks = optional(tile, "masks"))
        desc.masks = read_masks(*masks, field_path(path, "masks"));
    return desc;
}

SceneRect SceneReader::read_rect(const json& rect, const std::string& path) const {
    array_of(rect, path, 4, "4 numbers [x, y, width, height]");
    SceneRect r;
    // The GPU takes 32-bit floats: beyond 2^24 they no longer hold whole pixels (1e39 would be
    // Inf), and a size far below a pixel (1e-300) would be 0. Refuse both here, in one line.
    constexpr double kMaxCoordinate = 16777216.0;  // 2^24
    constexpr double kMinSize = 1.0 / 256.0;
    const auto coordinate = [&](size_t i) {
        const double v = finite_number(rect[i], item_path(path, i));
        if (std::abs(v) > kMaxCoordinate)
            fail(item_path(path, i),
                 "must lie within +-16777216 scene pixels (2^24, where 32-bit floats still hold "
                 "whole pixels), got " +
                     describe(rect[i]));
        return v;
    };
    r.x = coordinate(0);
    r.y = coordinate(1);
    r.width = coordinate(2);
    if (r.width <= 0) fail(item_path(path, 2), "width must be > 0, got " + describe(rect[2]));
    if (r.width < kMinSize)
        fail(item_path(path, 2), "width must be at least 1/256 pixel, got " + describe(rect[2]));
    r.height = coordinate(3);
    if (r.height <= 0) fail(item_path(path, 3), "height must be > 0, got " + describe(rect[3]));
    if (r.height < kMinSize)
        fail(item_path(path, 3), "height must be at least 1/256 pixel, got " + describe(rect[3]));
    return r;
}

// Kinds name shader inputs and texture slots, so they are kept to identifier characters.
bool valid_mask_kind(const std::string& kind) {
    return !kind.empty() && std::all_of(kind.begin(), kind.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    });
}

std::map<std::string, fs::path> SceneReader::read_masks(const json& masks,
                                                        const std::string& path) const {
    if (!masks.is_object()) fail(path, "must be an object, got " + describe(masks));
    std::map<std::string, fs::path> result;
    for (const auto& [kind, file] : masks.items()) {
        if (!valid_mask_kind(kind))
            fail(path, fmt::format("invalid mask kind {}: use lowercase letters, digits and _",
                                   json_quoted(kind)));
        result[kind] = existing_file(file, field_path(path, kind));
    }
    return result;
}

LightDesc SceneReader::read_light(const json& light, const std::string& path) const {
    expect_object(light, path, {"pos", "radius", "color", "intensity", "height"});
    LightDesc desc;
    const std::string pos_path = field_path(path, "pos");
    const json& pos = array_of(required(light, path, "pos"), pos_path, 2, "2 numbers [x, y]");
    for (size_t i = 0; i < 2; ++i) desc.pos[i] = finite_float(pos[i], item_path(pos_path, i));
    desc.radius =
        float_at_least(required(light, path, "radius"), field_path(path, "radius"), 0.0f, false);
    if (const json* color = optional(light, "color"))
        desc.color = read_color(*color, field_path(path, "color"));
    if (const json* intensity = optional(light, "intensity"))
        desc.intensity = float_at_least(*intensity, field_path(path, "intensity"), 0.0f, true);
    if (const json* height = optional(light, "height"))
        desc.height = float_at_least(*height, field_path(path, "height"), 0.0f, true);
    return desc;
}

std::array<float, 3> SceneReader::read_color(const json& color, const std::string& path) const {
    array_of(color, path, 3, "3 numbers [r, g, b]");
    std::array<float, 3> rgb{};
    for (size_t c = 0; c < 3; ++c)
        rgb[c] = float_at_least(color[c], item_path(path, c), 0.0f, true);
    return rgb;
}

SunDesc SceneReader::read_sun(const json& sun, const std::string& path) const {
    expect_object(sun, path, {"azimuth", "elevation", "color", "intensity"});
    SunDesc desc;
    desc.azimuth = finite_float(required(sun, path, "azimuth"), field_path(path, "azimuth"));
    const std::string elevation_path = field_path(path, "elevation");
    const json& elevation = required(sun, path, "elevation");
    desc.elevation = finite_float(elevation, elevation_path);
    if (desc.elevation < 0 || desc.elevation > 90)
        fail(elevation_path, "must be in [0, 90] degrees, got " + describe(elevation));
    if (const json* color = optional(sun, "color"))
        desc.color = read_color(*color, field_path(path, "color"));
    if (const json* intensity = optional(sun, "intensity"))
        desc.intensity = float_at_least(*intensity, field_path(path, "intensity"), 0.0f, true);
    return desc;
}

std::vector<EffectRef> SceneReader::read_effects(const json* list, const std::string& path) const {
    std::vector<EffectRef> effects;
    if (!list) return effects;
    if (!list->is_array()) fail(path, "must be an array, got " + describe(*list));
    for (size_t i = 0; i < list->size(); ++i)
        effects.push_back(read_effect((*list)[i], item_path(path, i)));
    return effects;
}

EffectRef SceneReader::read_effect(const json& effect, const std::string& path) const {
    expect_object(effect, path, {"plugin", "params", "preset"});
    EffectRef ref;
    ref.plugin = non_empty_string(required(effect, path, "plugin"), field_path(path, "plugin"));
    if (const json* params = optional(effect, "params")) {
        // Parameter names and ranges belong to the plugin; the plugin runtime checks them.
        if (!params->is_object())
            fail(field_path(path, "params"), "must be an object, got " + describe(*params));
        ref.params = *params;
    }
    if (const json* preset = optional(effect, "preset"))
        ref.preset = non_empty_string(*preset, field_path(path, "preset"));
    ref.where = path;
    return ref;
}

uint32_t SceneReader::read_active_floor(const json* value, size_t floor_count) const {
    if (!value) return uint32_t(floor_count - 1);
    const int64_t index = integer(*value, "active_floor");
    if (index < 0) fail("active_floor", "must be >= 0, got " + describe(*value));
    if (uint64_t(index) >= floor_count)
        fail("active_floor", fmt::format("must be < {} (the number of floors), got {}", floor_count,
                                         describe(*value)));
    return uint32_t(index);
}

}  // namespace

Result<SceneDesc> parse_scene_text(const std::string& text, const fs::path& file) {
    const std::string label = file.string();
    auto parsed = parse_json_strict(text, label);
    if (!parsed) return parsed.error();
    const json& root = parsed.value();

    std::error_code ec;
    fs::path absolute_file = fs::absolute(file, ec);
    if (ec) absolute_file = file;
    SceneReader reader(label, absolute_file.lexically_normal().parent_path());
    try {
        return reader.read(root, file);
    } catch (const ParseFailure& failure) {
        return failure.error;
    }
}

Result<SceneDesc> parse_scene_file(const fs::path& file) {
    auto text = read_input_file(file, kMaxSceneFileBytes, "a scene file");
    if (!text) {
        if (text.error().code != ErrorCode::FileNotFound) return text.error();
        // The absolute path as well: a relative name is often resolved against a surprise.
        std::error_code ec;
        const fs::path shown = fs::absolute(file, ec);
        return make_error(
            ErrorCode::FileNotFound,
            fmt::format("{}: file not found: {}", file.string(), (ec ? file : shown).string()));
    }
    return parse_scene_text(text.value(), file);
}

std::array<float, 3> SunDesc::direction() const {
    // In double, so that 90 degrees gives exactly (0, 0, 1) after rounding to float.
    const double pi = 3.14159265358979323846;
    const double az = double(azimuth) * pi / 180.0, el = double(elevation) * pi / 180.0;
    return {float(std::cos(el) * std::cos(az)), float(std::cos(el) * std::sin(az)),
            float(std::sin(el))};
}

}  // namespace acetate
