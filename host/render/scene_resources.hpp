#pragma once
// Everything a scene needs on the GPU that does not change per frame: tile textures (each file
// decoded and uploaded once), each floor's scene-space masks of the kinds effects need, and the
// geometry the frame planner works from. Built once at load; a floor switch touches none of it.

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/pixel_rect.hpp"
#include "render/frame_plan.hpp"
#include "scene/floor_masks.hpp"
#include "scene/scene.hpp"
#include "vulkan/gpu_image.hpp"

namespace acetate {

class VulkanContext;

struct LoadedTile {
    const GpuImage* texture = nullptr;
    SceneRect rect;
    PixelRect pixels;         // pixels it shades on the canvas (scene pixels, no camera)
    bool opaque = false;      // alpha is 1 at every texel
    bool one_to_one = false;  // drawn at its own size on whole pixels: texels map to pixels
};

struct LoadedFloor {
    std::string name;
    std::vector<LoadedTile> tiles;
    std::map<std::string, GpuImage> masks;  // kind -> scene-space composite, this floor's own
    FloorGeometry geometry;  // in scene pixels; the compositor plans in render pixels
};

class SceneResources {
  public:
    // Decodes and uploads every tile image in `texture_format`, and uploads each floor's mask
    // composites of `mask_kinds` (made once by composite_scene_masks, before effects were
    // built). Errors name the file.
    static Result<std::unique_ptr<SceneResources>> load(VulkanContext& context,
                                                        const SceneDesc& scene,
                                                        VkFormat texture_format,
                                                        const std::set<std::string>& mask_kinds,
                                                        const SceneMasks& masks = {});

    const std::vector<LoadedFloor>& floors() const { return floors_; }
    // Tile texels with a == 0 but rgb != 0, or NaN/Inf, summed over the files loaded. The tile
    // stage drops them (no colour without coverage), so they are reported here, once.
    uint64_t tile_texel_violations() const { return tile_texel_violations_; }
    // A transparent scene-size mask for floors without a kind some effect reads (so a shader
    // may texelFetch at canvas coordinates); null when every floor has every needed kind.
    const GpuImage* blank_mask() const { return blank_mask_ ? &*blank_mask_ : nullptr; }
    // Every GPU image held (textures and masks), for "what does the host hold" reports.
    std::vector<const GpuImage*> images() const;

  private:
    std::vector<std::unique_ptr<GpuImage>> textures_;
    std::vector<LoadedFloor> floors_;
    uint64_t tile_texel_violations_ = 0;
    std::optional<GpuImage> blank_mask_;
};

}  // namespace acetate
