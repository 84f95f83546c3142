#pragma once
// What every effect pass shares: one pipeline layout (a push-descriptor set with the frame
// uniforms at binding 0, up to 8 inputs at bindings 1..8, floor_data at binding 9), a linear
// clamp-to-edge sampler, and stand-ins for inputs a floor lacks (a transparent 1x1 texture for
// a missing mask, a 4-float buffer for missing floor data). Pipelines live in the PipelinePool,
// keyed by the SPIR-V's SHA-256, the output format and the blend.

#include <vulkan/vulkan.h>

#include <memory>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "plugins/effect_descriptor.hpp"
#include "vulkan/gpu_image.hpp"

namespace acetate {

class VulkanContext;
class PipelinePool;

class EffectPipelines {
  public:
    static constexpr uint32_t kMaxInputs = 8;
    static constexpr uint32_t kFrameBinding = 0;
    static constexpr uint32_t kFirstInputBinding = 1;
    static constexpr uint32_t kFloorDataBinding = 9;

    static Result<std::unique_ptr<EffectPipelines>> create(VulkanContext& context,
                                                           PipelinePool& pool);
    ~EffectPipelines();

    // The pipeline for a pass of this kind (ACETATE_PASS_*) with this fragment SPIR-V,
    // output format and blend (ACETATE_BLEND_*).
    Result<VkPipeline> pipeline(const std::vector<uint32_t>& fragment_spirv, VkFormat format,
                                uint32_t blend, uint32_t kind);

    VkPipelineLayout layout() const { return layout_; }
    VkSampler sampler() const { return sampler_; }
    const GpuImage& blank_texture() const { return blank_; }
    const GpuBuffer& empty_buffer() const { return empty_buffer_; }

  private:
    EffectPipelines(VulkanContext& context, PipelinePool& pool) : context_(context), pool_(pool) {}
    VulkanContext& context_;
    PipelinePool& pool_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkSampler sampler_ = VK_NULL_HANDLE;
    GpuImage blank_;
    GpuBuffer empty_buffer_;
};

// The frame uniforms as the GLSL block AcetateFrame lays them out (std140).
struct EffectFrameUniforms {
    float canvas[4];  // width, height, 1/width, 1/height
    float output[4];  // this pass's output size and its reciprocal
    float misc[4];    // time in seconds, floor index (-1 for global), 0, 0
    // followed by one vec4 per parameter (value in .x)
};

// The GLSL the host puts before a pass's source: version, the AcetateFrame block with a
// param_<name> macro per parameter, one sampler2D per input, floor_data, out_color. With
// `checked_builtins`, also checked_builtins_glsl(), so min, max, clamp and smoothstep in the
// pass's own text are the checked ones.
std::string effect_glsl_preamble(const EffectDescriptor& effect,
                                 const std::vector<std::string>& inputs, uint32_t kind,
                                 bool checked_builtins = false);

// GLSL that replaces min, max, clamp and smoothstep in the text after it with versions that
// return NaN where a floating-point operand is NaN, and smoothstep also where edge0 >= edge1
// (component-wise), so a result the built-in leaves driver-dependent or undefined shows as NaN.
// Integer forms forward to the built-ins unchanged; double forms are not provided.
std::string checked_builtins_glsl();

// The GLSL name of an input: '.' becomes '_' ("mask.water" -> "mask_water").
std::string input_variable(const std::string& input);

}  // namespace acetate
