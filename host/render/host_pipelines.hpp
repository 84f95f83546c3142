#pragma once
// The host's fixed-function stages, each its own pipeline with its own blend and stencil state
// (seed 000, A3: no state shared between stages, no property swaps at run time).

#include <vulkan/vulkan.h>

#include <array>
#include <map>
#include <string>
#include <vector>
#include <memory>

#include "core/result.hpp"

namespace acetate {

class VulkanContext;

// Push constants shared by every host stage (48 bytes; matches the GLSL `Push` blocks).
struct StagePushConstants {
    float rect[4] = {0, 0, 0, 0};   // tile rect in scene pixels
    float tint[4] = {0, 0, 0, 0};   // isolation tint, or the fill colour, or the background
    float canvas[2] = {0, 0};       // canvas size in pixels
    uint32_t floor_index = 0;       // violation counter slot; output: the view
    uint32_t mode = 0;              // tile: tint mode
};
static_assert(sizeof(StagePushConstants) == 48);

enum class Stage {
    TileToTarget,   // tile -> floor target; over blend; writes stencil = 1 where it covers
    TileToAccum,    // tile -> accumulation directly (floors without effects); over blend
    Composite,      // floor target -> accumulation; over blend; stencil EQUAL 1
    InjectCovered,    // test hook: colour -> floor target where stencil == 1
    InjectUncovered,  // test hook: colour -> floor target where stencil != 1
    Output,         // accumulation -> output image over the background, or a debug view
    Count
};
const char* stage_name(Stage stage);

class HostPipelines {
public:
    // Compiles the host shaders these stages use and creates one pipeline per stage for this
    // colour format; stages not asked for are neither compiled nor created.
    static Result<std::unique_ptr<HostPipelines>> create(VulkanContext& context,
                                                         VkFormat color_format,
                                                         const std::vector<Stage>& stages);
    ~HostPipelines();

    // The stage's pipeline; asking for a stage that was not created is a host bug.
    VkPipeline pipeline(Stage stage) const;
    VkPipelineLayout layout() const { return layout_; }
    VkSampler linear_sampler() const { return linear_sampler_; }
    VkSampler nearest_sampler() const { return nearest_sampler_; }

    // Binding slots of the one push-descriptor set all stages share.
    static constexpr uint32_t kPrimaryImage = 0;    // tile, floor target or accumulation
    static constexpr uint32_t kSecondaryImage = 1;  // output: the active floor's target
    static constexpr uint32_t kViolationBuffer = 2;

private:
    explicit HostPipelines(VulkanContext& context) : context_(context) {}
    Result<void> create_layout();
    Result<VkShaderModule> shader_module(const char* name);
    Result<void> create_stage(Stage stage, VkFormat color_format);

    VulkanContext& context_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkSampler linear_sampler_ = VK_NULL_HANDLE;
    VkSampler nearest_sampler_ = VK_NULL_HANDLE;
    std::array<VkPipeline, size_t(Stage::Count)> pipelines_{};
    std::map<std::string, VkShaderModule> modules_;  // only during create()
};

}  // namespace acetate
