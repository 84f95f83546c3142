#pragma once
// What every effect pass shares: one pipeline layout (a push-descriptor set with the frame
// uniforms at binding 0, up to 8 inputs at bindings 1..8, floor_data at binding 9, the lights
// at binding 10, the frame uniforms again at binding 11; the camera as push constants), a linear
// clamp-to-edge sampler, and stand-ins for inputs a floor lacks (a transparent 1x1 texture for a
// missing mask, a 4-float buffer for missing floor data). Pipelines live in the PipelinePool, keyed
// by the SPIR-V's SHA-256, the output format and the blend.

#include <vulkan/vulkan.h>

#include <memory>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "plugins/effect_descriptor.hpp"
#include "plugins/effect_graph.hpp"
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
    static constexpr uint32_t kLightsBinding = 10;  // ABI 1.1: the floor's lights
    // The same frame block as binding 0, as a read-only storage buffer: what the GLSL preamble
    // and the instanced-quad vertex shader declare. Mesa 22.3's lavapipe inlines uniform-buffer
    // values that branch conditions read and compiles (and keeps) a new shader variant at every
    // draw, which grew the host by 1.8 MiB a frame with the water effect; storage-buffer loads
    // are never inlined. Binding 0 stays the documented block for whole SPIR-V modules.
    static constexpr uint32_t kFrameStorageBinding = 11;

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

// ABI 1.2: the camera, as the push-constant block AcetateView lays it out (both stages).
struct EffectViewPushConstants {
    float view[4];          // origin x, y (scene pixels), scale, 1 / scale
    float scene_canvas[4];  // the scene's canvas: width, height, 1/width, 1/height
};
static_assert(sizeof(EffectViewPushConstants) == 32);

// One light as the GLSL block AcetateLights lays it out (std430: 48 bytes).
struct EffectLightGpu {
    float position[2];
    float height, radius;
    float color[3];
    float intensity;
    float direction[3];
    uint32_t kind;
};
static_assert(sizeof(EffectLightGpu) == 48);

// How the preamble declares AcetateFrame: as GLSL passes read it (the storage buffer at
// kFrameStorageBinding), or as the uniform block at binding 0 that effect.h documents for whole
// SPIR-V modules (tests compile their stand-ins for shipped SPIR-V with it).
enum class FrameBlockDeclaration { Storage, Uniform };

// The GLSL the host puts before a pass's source: version, the AcetateFrame block with a
// param_<name> macro per parameter and phase_<name> per phase, one sampler2D per input (named
// as the pass chose) with its acetate_size_<name>, floor_data, the lights block, out_color.
// With `checked_builtins`, also checked_builtins_glsl(), so min, max, clamp, smoothstep and
// texelFetch in the pass's own text are the checked ones. Then the pass's defines and `#line 1`.
std::string effect_glsl_preamble(const EffectDescriptor& effect, const GraphPass& pass,
                                 const std::vector<GraphPhase>& phases,
                                 bool checked_builtins = false,
                                 FrameBlockDeclaration frame = FrameBlockDeclaration::Storage);
// The same for a pass with default input names and no phases (tests).
std::string effect_glsl_preamble(const EffectDescriptor& effect,
                                 const std::vector<std::string>& inputs, uint32_t kind,
                                 bool checked_builtins = false,
                                 FrameBlockDeclaration frame = FrameBlockDeclaration::Storage);

// GLSL that replaces min, max, clamp and smoothstep in the text after it with versions that
// return NaN where a floating-point operand is NaN, and smoothstep also where edge0 >= edge1
// (component-wise), so a result the built-in leaves driver-dependent or undefined shows as NaN.
// Integer forms forward to the built-ins unchanged; double forms are not provided.
std::string checked_builtins_glsl();

}  // namespace acetate
