#pragma once
// The host's own passes (HostPass: tiles, composite, output; not an effect's passes, and not a
// validation stage), each its own pipeline with its own blend and stencil state: no state
// shared between passes, no property swaps at run time (docs/design.md, L-separate-stages).

#include <vulkan/vulkan.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace acetate {

class VulkanContext;
class PipelinePool;

// Each host pass's push constants, field for field its shaders' `Push` block (GLSL std430
// offsets: the vec4s first). The layout has one range, as large as the largest of them.
struct TilePushConstants {         // tile.vert, tile.frag
    float tile_rect[4] = {};       // x, y, width, height in scene pixels
    float isolation_tint[4] = {};  // the floor's tint (rgb); only the isolation variants read it
    float view[4] = {0, 0, 1, 1};  // the camera: origin x, y (scene pixels), scale, 1/scale
    float canvas_size[2] = {};     // the output, in pixels
};
struct CompositePushConstants {   // composite.frag
    uint32_t violation_slot = 0;  // the floor's counter in the violation buffer
};
struct InjectPushConstants {  // inject.frag
    float colour[4] = {};     // what the test hook paints (premultiplied)
};
struct OutputPushConstants {   // output.frag
    float background[4] = {};  // the canvas background, straight alpha, linear
    uint32_t view = 0;         // OutputView (render/output_view.hpp)
};
struct MaskViewPushConstants {  // mask_view.frag
    float view[4] = {};         // origin x, y (scene pixels), scale, 1/scale
    float canvas[4] = {};       // the scene's canvas: width, height, 1/width, 1/height
};
static_assert(sizeof(MaskViewPushConstants) == 32 && sizeof(TilePushConstants) == 56 &&
              sizeof(CompositePushConstants) == 4 && sizeof(InjectPushConstants) == 16 &&
              sizeof(OutputPushConstants) == 20);
inline constexpr uint32_t kHostPushConstantBytes = sizeof(TilePushConstants);

enum class HostPass {
    TileToTarget,      // tile -> floor target; over blend; writes stencil = 1 where it covers
    TileToAccum,       // tile -> accumulation directly (floors without effects); over blend
    Composite,         // floor target -> accumulation; over blend; stencil EQUAL 1
    CompositeByAlpha,  // same, no stencil gate: drops exact (0,0,0,0) (coverage-expanding)
    InjectCovered,     // test hook: colour -> floor target where stencil == 1
    InjectUncovered,   // test hook: colour -> floor target where stencil != 1
    Output,            // accumulation -> output image over the background, or a debug view
    // The tile passes as the isolation view draws them: the tint is compiled in, not chosen by a
    // push constant, because lavapipe runs both sides of such a branch for every pixel.
    TileToTargetIsolation,
    TileToAccumIsolation,
    MaskView,  // a floor's scene-space mask -> its render-pixel copy under a camera; replace
    Count
};
const char* host_pass_name(HostPass pass);
// The pass a view draws `pass` with: the isolation variant of a tile pass in the isolation
// view, otherwise `pass` itself. Load (which prepares pipelines) and bind go through this alike.
HostPass view_variant(HostPass pass, bool isolation);

// Process-wide (one per Renderer): the layout and samplers all host passes share, and their
// pipelines per pass and colour format, kept in the PipelinePool so they survive scenes.
class HostPipelines {
  public:
    static Result<std::unique_ptr<HostPipelines>> create(VulkanContext& context,
                                                         PipelinePool& pool);
    ~HostPipelines();

    // Makes sure the pass's pipeline for this colour format exists: compiles its shaders and
    // creates it on first request only. Called at load; never during a frame.
    Result<void> ensure(HostPass pass, VkFormat color_format);
    // The pass's pipeline; asking for one that ensure() did not make is a host bug.
    VkPipeline pipeline(HostPass pass, VkFormat color_format) const;
    VkPipelineLayout layout() const { return layout_; }
    // Records a pass's push constants (one of the structs above).
    template <typename PushConstants>
    void push(VkCommandBuffer cmd, const PushConstants& constants) const {
        static_assert(sizeof(PushConstants) <= kHostPushConstantBytes &&
                      sizeof(PushConstants) % 4 == 0);
        vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                           0, sizeof(PushConstants), &constants);
    }
    VkSampler linear_sampler() const { return linear_sampler_; }
    VkSampler nearest_sampler() const { return nearest_sampler_; }
    // The sampler a tile is drawn with. One drawn 1:1 on whole pixels samples nearest, which at
    // pixel centres reads exactly its own texel (as texelFetch would, without the branch in the
    // shader that chose between the two); a scaled one filters. lavapipe compiles a shader
    // variant per sampler state, so the warm-up draws each texture with the samplers it gets.
    VkSampler tile_sampler(bool one_to_one) const {
        return one_to_one ? nearest_sampler_ : linear_sampler_;
    }

    // Binding slots of the one push-descriptor set all host passes share.
    static constexpr uint32_t kPrimaryImage = 0;    // tile, floor target or accumulation
    static constexpr uint32_t kSecondaryImage = 1;  // output: the active floor's target
    static constexpr uint32_t kViolationBuffer = 2;

  private:
    HostPipelines(VulkanContext& context, PipelinePool& pool) : context_(context), pool_(pool) {}
    Result<void> create_layout();
    Result<VkPipeline> create_pass(HostPass pass, VkFormat color_format, VkPipelineCache cache);

    VulkanContext& context_;
    PipelinePool& pool_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkSampler linear_sampler_ = VK_NULL_HANDLE;
    VkSampler nearest_sampler_ = VK_NULL_HANDLE;
    std::map<std::pair<HostPass, VkFormat>, VkPipeline> pipelines_;  // owned by the pool
};

}  // namespace acetate
