#include "scene/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string_view>
#include <utility>

#include "core/input_file.hpp"
#include "core/json_fields.hpp"
#include "core/strict_json.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
// The reader's checks (required, optional, expect_object, text, integer, ...) and its errors:
// a failed check throws, parse_scene_text turns it into the one-line Result.
using namespace json_fields;

constexpr std::string_view kFormat = "acetate-scene/1";
// Far above any real device limit; the renderer checks the device's own limit later.
constexpr int64_t kMaxCanvasSide = 65536;
// Effects consider a few dozen lights per floor (lighting's ultra preset: 64); 4096 leaves room
// for any real scene while a hostile one is refused before 100,000 lights cost seconds of load.
constexpr size_t kMaxLightsPerFloor = 4096;

class SceneReader {
  public:
    explicit SceneReader(fs::path base_dir) : base_dir_(std::move(base_dir)) {}

    SceneDesc read(const json& root, const fs::path& file);

  private:
    const json& array_of(const json& value, const std::string& path, size_t count,
                         std::string_view shape) const;
    float float_at_least(const json& value, const std::string& path, float min, bool inclusive,
                         std::string_view what = "") const;
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

    fs::path base_dir_;
};

const json& SceneReader::array_of(const json& value, const std::string& path, size_t count,
                                  std::string_view shape) const {
    if (!value.is_array())
        fail(path, fmt::format("must be an array of {}, got {}", shape, describe(value)));
    if (value.size() != count)
        fail(path, fmt::format("must be an array of {}, got {} elements", shape, value.size()));
    return value;
}

float SceneReader::float_at_least(const json& value, const std::string& path, float min,
                                  bool inclusive, std::string_view what) const {
    const float number = finite_float(value, path);
    if (inclusive ? number >= min : number > min) return number;
    const std::string subject = what.empty() ? "must be" : fmt::format("{} must be", what);
    fail(path,
         fmt::format("{} {} {}, got {}", subject, inclusive ? ">=" : ">", min, describe(value)));
}

// Paths are relative to the scene file; existence is checked now so that a typo is reported
// with its JSON path instead of surfacing later as a decode failure.
fs::path SceneReader::existing_file(const json& value, const std::string& path) const {
    const std::string text = non_empty_text(value, path);
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
    expect_object(root, "", {}, {"format", "canvas", "floors", "global_effects", "active_floor"});

    SceneDesc scene;
    scene.file = file;
    read_canvas(required(root, "", "canvas"), "canvas", scene);

    const json& floors = required(root, "", "floors");
    if (!floors.is_array()) fail("floors", "must be an array, got " + describe(floors));
    if (floors.empty()) fail("floors", "at least one floor is required");
    std::map<std::string, size_t> first_index_of_name;
    for (size_t i = 0; i < floors.size(); ++i) {
        const std::string path = element("floors", i);
        scene.floors.push_back(read_floor(floors[i], path));
        const auto [it, inserted] = first_index_of_name.emplace(scene.floors.back().name, i);
        if (!inserted)
            fail(field(path, "name"),
                 fmt::format("duplicate floor name {} (also floors[{}].name)",
                             json_quoted(scene.floors.back().name), it->second));
    }
    scene.global_effects = read_effects(optional(root, "global_effects"), "global_effects");
    scene.active_floor = read_active_floor(optional(root, "active_floor"), floors.size());
    return scene;
}

void SceneReader::read_canvas(const json& canvas, const std::string& path, SceneDesc& scene) const {
    expect_object(canvas, path, {}, {"width", "height", "background"});
    scene.width = canvas_side(required(canvas, path, "width"), field(path, "width"));
    scene.height = canvas_side(required(canvas, path, "height"), field(path, "height"));
    if (const json* background = optional(canvas, "background"))
        scene.background = read_background(*background, field(path, "background"));
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
    for (size_t c = 0; c < 3; ++c) rgba[c] = float_at_least(value[c], element(path, c), 0.0f, true);
    rgba[3] = finite_float(value[3], element(path, 3));
    if (rgba[3] < 0.0f || rgba[3] > 1.0f)
        fail(element(path, 3), "alpha must be in [0, 1], got " + describe(value[3]));
    return rgba;
}

FloorDesc SceneReader::read_floor(const json& floor, const std::string& path) const {
    expect_object(floor, path, {}, {"name", "tiles", "lights", "sun", "effects"});
    FloorDesc desc;
    desc.name = non_empty_text(required(floor, path, "name"), field(path, "name"));

    const std::string tiles_path = field(path, "tiles");
    const json& tiles = required(floor, path, "tiles");
    if (!tiles.is_array()) fail(tiles_path, "must be an array, got " + describe(tiles));
    for (size_t i = 0; i < tiles.size(); ++i)
        desc.tiles.push_back(read_tile(tiles[i], element(tiles_path, i)));

    if (const json* lights = optional(floor, "lights")) {
        const std::string lights_path = field(path, "lights");
        if (!lights->is_array()) fail(lights_path, "must be an array, got " + describe(*lights));
        if (lights->size() > kMaxLightsPerFloor)
            fail(lights_path, fmt::format("{} lights is over the limit of {} per floor",
                                          lights->size(), kMaxLightsPerFloor));
        for (size_t i = 0; i < lights->size(); ++i)
            desc.lights.push_back(read_light((*lights)[i], element(lights_path, i)));
    }
    if (const json* sun = optional(floor, "sun")) desc.sun = read_sun(*sun, field(path, "sun"));
    desc.effects = read_effects(optional(floor, "effects"), field(path, "effects"));
    return desc;
}

TileDesc SceneReader::read_tile(const json& tile, const std::string& path) const {
    expect_object(tile, path, {}, {"image", "rect", "masks"});
    TileDesc desc;
    desc.image = existing_file(required(tile, path, "image"), field(path, "image"));
    desc.rect = read_rect(required(tile, path, "rect"), field(path, "rect"));
    if (const json* masks = optional(tile, "masks"))
        desc.masks = read_masks(*masks, field(path, "masks"));
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
        const double v = finite_number(rect[i], element(path, i));
        if (std::abs(v) > kMaxCoordinate)
            fail(element(path, i),
                 "must lie within +-16777216 scene pixels (2^24, where 32-bit floats still hold "
                 "whole pixels), got " +
                     describe(rect[i]));
        return v;
    };
    r.x = coordinate(0);
    r.y = coordinate(1);
    r.width = coordinate(2);
    if (r.width <= 0) fail(element(path, 2), "width must be > 0, got " + describe(rect[2]));
    if (r.width < kMinSize)
        fail(element(path, 2), "width must be at least 1/256 pixel, got " + describe(rect[2]));
    r.height = coordinate(3);
    if (r.height <= 0) fail(element(path, 3), "height must be > 0, got " + describe(rect[3]));
    if (r.height < kMinSize)
        fail(element(path, 3), "height must be at least 1/256 pixel, got " + describe(rect[3]));
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
        result[kind] = existing_file(file, field(path, kind));
    }
    return result;
}

LightDesc SceneReader::read_light(const json& light, const std::string& path) const {
    expect_object(light, path, {}, {"pos", "radius", "color", "intensity", "height"});
    LightDesc desc;
    const std::string pos_path = field(path, "pos");
    const json& pos = array_of(required(light, path, "pos"), pos_path, 2, "2 numbers [x, y]");
    for (size_t i = 0; i < 2; ++i) desc.pos[i] = finite_float(pos[i], element(pos_path, i));
    desc.radius =
        float_at_least(required(light, path, "radius"), field(path, "radius"), 0.0f, false);
    if (const json* color = optional(light, "color"))
        desc.color = read_color(*color, field(path, "color"));
    if (const json* intensity = optional(light, "intensity"))
        desc.intensity = float_at_least(*intensity, field(path, "intensity"), 0.0f, true);
    if (const json* height = optional(light, "height"))
        desc.height = float_at_least(*height, field(path, "height"), 0.0f, true);
    return desc;
}

std::array<float, 3> SceneReader::read_color(const json& color, const std::string& path) const {
    array_of(color, path, 3, "3 numbers [r, g, b]");
    std::array<float, 3> rgb{};
    for (size_t c = 0; c < 3; ++c) rgb[c] = float_at_least(color[c], element(path, c), 0.0f, true);
    return rgb;
}

SunDesc SceneReader::read_sun(const json& sun, const std::string& path) const {
    expect_object(sun, path, {}, {"azimuth", "elevation", "color", "intensity"});
    SunDesc desc;
    desc.azimuth = finite_float(required(sun, path, "azimuth"), field(path, "azimuth"));
    const std::string elevation_path = field(path, "elevation");
    const json& elevation = required(sun, path, "elevation");
    desc.elevation = finite_float(elevation, elevation_path);
    if (desc.elevation < 0 || desc.elevation > 90)
        fail(elevation_path, "must be in [0, 90] degrees, got " + describe(elevation));
    if (const json* color = optional(sun, "color"))
        desc.color = read_color(*color, field(path, "color"));
    if (const json* intensity = optional(sun, "intensity"))
        desc.intensity = float_at_least(*intensity, field(path, "intensity"), 0.0f, true);
    return desc;
}

std::vector<EffectRef> SceneReader::read_effects(const json* list, const std::string& path) const {
    std::vector<EffectRef> effects;
    if (!list) return effects;
    if (!list->is_array()) fail(path, "must be an array, got " + describe(*list));
    for (size_t i = 0; i < list->size(); ++i)
        effects.push_back(read_effect((*list)[i], element(path, i)));
    return effects;
}

EffectRef SceneReader::read_effect(const json& effect, const std::string& path) const {
    expect_object(effect, path, {}, {"plugin", "params", "preset"});
    EffectRef ref;
    ref.plugin = non_empty_text(required(effect, path, "plugin"), field(path, "plugin"));
    if (const json* params = optional(effect, "params")) {
        // Parameter names and ranges belong to the plugin; the plugin runtime checks them.
        if (!params->is_object())
            fail(field(path, "params"), "must be an object, got " + describe(*params));
        ref.params = *params;
    }
    if (const json* preset = optional(effect, "preset"))
        ref.preset = non_empty_text(*preset, field(path, "preset"));
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
    SceneReader reader(absolute_file.lexically_normal().parent_path());
    return json_fields::read_json(label, [&] { return reader.read(root, file); });
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

namespace {

// Cosine and sine of an angle in degrees, exact at multiples of 90: in radians 90 degrees is
// not representable, and cos(pi / 2) is 6.1e-17, which would hand an effect a sun overhead at
// (5.3e-17, 3.1e-17, 1) instead of the (0, 0, 1) the scene says.
std::pair<double, double> cos_sin_degrees(double degrees) {
    double turn = std::fmod(degrees, 360.0);
    if (turn < 0) turn += 360.0;
    if (turn == 0) return {1, 0};
    if (turn == 90) return {0, 1};
    if (turn == 180) return {-1, 0};
    if (turn == 270) return {0, -1};
    const double radians = turn * 3.14159265358979323846 / 180.0;
    return {std::cos(radians), std::sin(radians)};
}

}  // namespace

std::array<float, 3> SunDesc::direction() const {
    const auto [cos_az, sin_az] = cos_sin_degrees(azimuth);
    const auto [cos_el, sin_el] = cos_sin_degrees(elevation);
    return {float(cos_el * cos_az), float(cos_el * sin_az), float(sin_el)};
}

}  // namespace acetate
