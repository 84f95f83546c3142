#pragma once
// The images, masks and lights the harness's scenes are made of: deterministic functions of a
// case's pattern, size, floor and seed, so a failing case can be rebuilt exactly. Values are
// premultiplied linear RGBA, already rounded to half floats (what an rgba16f target holds), so
// the harness's "input" is exactly what the tile pass draws.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "case_spec.hpp"
#include "core/result.hpp"
#include "scene/image_io.hpp"
#include "scene/scene.hpp"

namespace acetate::harness {

struct FloorInput {
    std::string name;   // unique among the scene's floors
    bool tiled = true;  // false: a floor with no tile at all (the rect and images unused)
    uint32_t x = 0, y = 0, width = 0, height = 0;  // the tile's rect on the canvas, whole pixels
    ImageRGBA image;                               // width x height
    std::map<std::string, ImageRGBA> masks;        // kind -> data mask, width x height
    std::vector<LightDesc> lights;
    std::optional<SunDesc> sun;
};

// Floor `floor` of `floors`: floor 0 covers the whole canvas, higher floors alternate between
// two overlapping sub-rectangles, so each floor has pixels no other floor above it covers.
// Its pixels follow `pattern`, its lights `lights` and its masks (one per kind in `mask_kinds`)
// `masks`.
struct InputChoice {
    Pattern pattern = Pattern::Standard;
    LightSet lights = LightSet::Standard;
    MaskFill masks = MaskFill::Content;
    FloorVariant floor_variant = FloorVariant::Standard;
};
FloorInput make_floor_input(const InputChoice& choice, uint32_t canvas_width,
                            uint32_t canvas_height, uint32_t floor, uint32_t floors, uint64_t seed,
                            const std::vector<std::string>& mask_kinds);
// The same with three lights over the canvas and masks with content.
FloorInput make_floor_input(Pattern pattern, uint32_t canvas_width, uint32_t canvas_height,
                            uint32_t floor, uint32_t floors, uint64_t seed,
                            const std::vector<std::string>& mask_kinds);

// Which effects go on a floor or on the composite, with their scene params.
struct SceneEffect {
    std::string plugin;
    nlohmann::json params = nlohmann::json::object();
    std::string preset;
};
struct SceneLayout {
    uint32_t width = 0, height = 0;
    std::vector<FloorInput> floors;
    std::vector<std::vector<SceneEffect>> floor_effects;  // per floor
    std::vector<SceneEffect> global_effects;
};

// Writes the layout's images (EXR) into `directory` and parses the scene that names them, as
// `acetate render` would read it. `name` distinguishes several scenes in one directory.
Result<SceneDesc> write_scene(const SceneLayout& layout, const std::filesystem::path& directory,
                              const std::string& name);

// Rounds every value to the nearest half float (as an rgba16f target stores it).
void round_to_half(ImageRGBA& image);

}  // namespace acetate::harness
