#pragma once
// The render targets of one loaded scene, owned here and listed once (images()): what a frame
// draws into, what the warm-up clears and what the statistics report. Allocated at load, at the
// canvas size; a frame allocates nothing.

#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "render/effect_runtime.hpp"
#include "render/frame_stats.hpp"
#include "vulkan/gpu_image.hpp"

namespace acetate {

class VulkanContext;

// Which of the optional targets a scene needs.
struct FrameTargetNeeds {
    // Some floor is drawn through a target of its own (it has effects, a debug view reads it,
    // or the test hook paints into it): the floor colour target and its stencil.
    bool floor_target = false;
    bool floor_effects = false;   // some floor has effects: their ping-pong partner
    bool global_effects = false;  // the composite's ping-pong partner
    size_t floor_count = 0;       // one violation counter each
};

class FrameTargets {
  public:
    // Allocates the targets `needs` asks for, `width` x `height` in `format` (the stencil in
    // the device's stencil format). Errors start with `where` (the scene file's canvas field).
    Result<void> allocate(VulkanContext& context, uint32_t width, uint32_t height, VkFormat format,
                          const FrameTargetNeeds& needs, const std::string& where);

    GpuImage& accumulation() { return accumulation_; }  // the floors composited so far
    GpuImage& output() { return output_; }              // over the background, or a view
    // Null where the scene does not need them (FrameTargetNeeds).
    GpuImage* accumulation_pingpong() { return opt(accumulation_pingpong_); }
    GpuImage* floor_colour() { return opt(floor_colour_); }
    GpuImage* floor_stencil() { return opt(floor_stencil_); }
    GpuImage* floor_pingpong() { return opt(floor_pingpong_); }
    // One uint per floor: pixels reaching its composite with colour at alpha 0, or NaN/Inf.
    GpuBuffer& violations() { return violations_; }
    // What effect passes write besides "result", made while the instances are built.
    EffectTargets& effect_targets() { return effect_targets_; }

    // Every target held, the stencil included, in the order the statistics list them.
    std::vector<GpuImage*> images();
    std::vector<const GpuImage*> images() const;
    std::vector<TargetInfo> infos() const;

  private:
    template <typename Self>
    static auto list_images(Self& self);  // the one list both images() return
    static GpuImage* opt(std::optional<GpuImage>& image) { return image ? &*image : nullptr; }

    GpuImage accumulation_;
    GpuImage output_;
    std::optional<GpuImage> accumulation_pingpong_;
    std::optional<GpuImage> floor_colour_;
    std::optional<GpuImage> floor_stencil_;
    std::optional<GpuImage> floor_pingpong_;
    GpuBuffer violations_;
    EffectTargets effect_targets_;
};

}  // namespace acetate
