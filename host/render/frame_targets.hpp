#pragma once
// The render targets of one loaded scene, owned here and listed once (images()): what a frame
// draws into, what the warm-up clears and what the statistics report. Allocated at load, at the
// canvas size; a frame allocates nothing.
//
// Three roles are played by images a frame uses only between its own passes: a floor's own
// colour target, its effects' ping-pong partner and the composite's ping-pong partner (global
// effects). Each compiled frame gives the roles images by when it uses them (share_images in
// frame_graph.hpp), so roles used at different times share one: the floors' roles are in use
// together, the composite's partner only after the last floor, beside at most one of them (the
// floor a debug view shows). Two images therefore hold all three, and a scene with floor and
// global effects holds one canvas-size image less than one per role.

#include <array>
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
    // Roles used at different times share an image (off: one image per role, to compare).
    bool share_roles = true;
};

enum class SharedRole : uint8_t { FloorColour, FloorPingpong, CompositePingpong };
constexpr size_t kSharedRoles = 3;
const char* to_string(SharedRole role);

// The image that plays each role in one frame; null for a role the scene does not have.
struct RoleImages {
    std::array<GpuImage*, kSharedRoles> image{};
    GpuImage* operator[](SharedRole role) const { return image[size_t(role)]; }
};

class FrameTargets {
  public:
    // Allocates the targets `needs` asks for, `width` x `height` in `format` (the stencil in
    // the device's stencil format). Errors start with `where` (the scene file's canvas field).
    Result<void> allocate(VulkanContext& context, uint32_t width, uint32_t height, VkFormat format,
                          const FrameTargetNeeds& needs, const std::string& where);

    GpuImage& accumulation() { return accumulation_; }  // the floors composited so far
    GpuImage& output() { return output_; }              // over the background, or a view
    // Null where the scene has no floor target (FrameTargetNeeds::floor_target).
    GpuImage* floor_stencil() { return opt(floor_stencil_); }
    bool has(SharedRole role) const { return stand_ins_[size_t(role)].has_value(); }
    // An image without Vulkan objects per role the scene has (GpuImage::stand_in), for the
    // frame compiled to learn when each role is used.
    RoleImages stand_ins();
    // The images the roles share (none, one or two), in the order share_images numbers them.
    std::vector<GpuImage>& shared() { return shared_; }
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
    std::vector<GpuImage> shared_;
    std::array<std::optional<GpuImage>, kSharedRoles> stand_ins_;
    std::optional<GpuImage> floor_stencil_;
    GpuBuffer violations_;
    EffectTargets effect_targets_;
};

}  // namespace acetate
