#pragma once
// The scene description as read from an `acetate-scene/1` JSON file (docs/scene-format.md).
// Pure data: nothing here touches the GPU or reads images.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace acetate {

// An axis-aligned rectangle in scene pixels: origin top-left, y down.
struct SceneRect {
    double x = 0, y = 0, width = 0, height = 0;
};

struct TileDesc {
    std::filesystem::path image;  // absolute (resolved against the scene file)
    SceneRect rect;               // the image is scaled to fill this
    std::map<std::string, std::filesystem::path> masks;  // kind ("water", ...) -> absolute path
};

struct LightDesc {
    std::array<float, 2> pos{0, 0};       // scene pixels
    float radius = 0;                     // scene pixels, > 0
    std::array<float, 3> color{1, 1, 1};  // linear
    float intensity = 1;                  // >= 0
    float height = 0;                     // above the floor, scene pixels, >= 0 (default: on it)
};

// A floor's directional light. Azimuth: degrees in the scene plane from +x towards +y (so
// clockwise on screen, y being down): 0 means the light comes from the right. Elevation: degrees
// above the floor, 0 (grazing) to 90 (straight down onto it).
struct SunDesc {
    float azimuth = 0;
    float elevation = 45;
    std::array<float, 3> color{1, 1, 1};  // linear
    float intensity = 1;                  // >= 0

    // Unit vector from the floor towards the sun: x right, y down, z up out of the floor.
    std::array<float, 3> direction() const;
};

// A reference to an effect plugin as the scene names it; checked against the plugin at load.
struct EffectRef {
    std::string plugin;  // reverse-DNS id, e.g. "acetate.lighting"
    nlohmann::json params = nlohmann::json::object();
    std::string preset;  // empty when not given
    std::string where;   // e.g. "floors[1].effects[0]" for error messages
};

struct FloorDesc {
    std::string name;
    std::vector<TileDesc> tiles;
    std::vector<LightDesc> lights;
    std::optional<SunDesc> sun;
    std::vector<EffectRef> effects;
};

struct SceneDesc {
    std::filesystem::path file;                   // the scene file, for messages
    uint32_t width = 0, height = 0;               // canvas size in pixels
    std::array<float, 4> background{0, 0, 0, 1};  // linear, straight alpha as written
    std::vector<FloorDesc> floors;                // bottom to top
    std::vector<EffectRef> global_effects;
    uint32_t active_floor = 0;  // defaults to the top floor when absent
};

// Reads and validates a scene file. Errors are one line naming the file and the JSON path of
// the field at fault, e.g. `scene.json: floors[1].tiles[0].rect[2]: width must be > 0, got -5`.
// Image files are checked for existence here; decoding happens at load.
Result<SceneDesc> parse_scene_file(const std::filesystem::path& file);

// Same, from text already in memory; `file` names it in messages and anchors relative paths.
Result<SceneDesc> parse_scene_text(const std::string& text, const std::filesystem::path& file);

}  // namespace acetate
