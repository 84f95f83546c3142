#include "scene/floor_masks.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "scene/mask_compositor.hpp"

namespace acetate {

Result<SceneMasks> composite_scene_masks(const SceneDesc& scene,
                                         const std::set<std::string>& kinds) {
    SceneMasks out;
    if (kinds.empty()) {
        out.floors.resize(scene.floors.size());
        return out;
    }
    MaskImages decoded;  // by path: a file shared by tiles decodes once
    for (size_t f = 0; f < scene.floors.size(); ++f) {
        const std::vector<TileDesc>& tiles = scene.floors[f].tiles;
        for (size_t t = 0; t < tiles.size(); ++t)
            for (const auto& [kind, path] : tiles[t].masks) {
                if (!kinds.count(kind) || decoded.count(path)) continue;
                auto mask = load_image(path, ImageRole::Mask);
                if (!mask)
                    return make_error(
                        mask.error().code,
                        fmt::format("{}: floors[{}].tiles[{}].masks.{}: {}", scene.file.string(), f,
                                    t, kind, mask.error().message));
                ++out.files_decoded;
                decoded.emplace(path, std::move(mask.value()));
            }
    }
    for (const FloorDesc& floor : scene.floors) {
        FloorMasks masks;
        for (const std::string& kind : kinds)
            if (std::any_of(floor.tiles.begin(), floor.tiles.end(),
                            [&](const TileDesc& t) { return t.masks.count(kind) != 0; }))
                masks.emplace(
                    kind, composite_floor_mask(floor, kind, scene.width, scene.height, decoded));
        out.floors.push_back(std::move(masks));
    }
    return out;
}

}  // namespace acetate
