#pragma once
// Each floor's masks, decoded and composited on the CPU once per load, before any effect is
// built: build() reads them (ABI 1.1 read_mask) and the GPU path uploads these same images, so
// nothing is decoded twice. Only the kinds some loaded effect declared are decoded.

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "scene/image_io.hpp"
#include "scene/scene.hpp"

namespace acetate {

// kind -> the floor's scene-space composite of that kind (composite_floor_mask). Only kinds the
// floor has: a kind absent from the floor is absent from the map.
using FloorMasks = std::map<std::string, ImageRGBA>;

struct SceneMasks {
    std::vector<FloorMasks> floors;  // one per scene floor
    uint64_t files_decoded = 0;      // each mask file once, however many tiles name it
};

// Decodes the masks of `kinds` named by the scene's tiles and composites them per floor.
// Errors name the scene file and field, e.g.
// `scene.json: floors[0].tiles[2].masks.water: cannot decode ...`.
Result<SceneMasks> composite_scene_masks(const SceneDesc& scene,
                                         const std::set<std::string>& kinds);

}  // namespace acetate
