#pragma once
// One graphics pipeline as every pass of Acetate needs it: two shader stages, no vertex input,
// one colour attachment (dynamic rendering), dynamic viewport and scissor, an optional stencil
// test and one of three blends. Host stages and effect passes differ only in these fields.

#include <vulkan/vulkan.h>

#include "core/result.hpp"

namespace acetate {

enum class BlendMode {
    Replace,  // the fragment replaces the pixel
    Add,      // src + dst, colour and alpha alike
    Over,     // premultiplied over: src + dst * (1 - src.a), colour and alpha alike
};

struct GraphicsPipelineDesc {
    VkShaderModule vertex = VK_NULL_HANDLE;
    VkShaderModule fragment = VK_NULL_HANDLE;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkFormat color_format = VK_FORMAT_UNDEFINED;
    // A stencil attachment of this format (and its depth aspect, for combined formats), or none.
    VkFormat stencil_format = VK_FORMAT_UNDEFINED;
    bool stencil_test = false;  // compare against reference 1
    VkCompareOp stencil_compare = VK_COMPARE_OP_ALWAYS;
    bool stencil_write = false;  // write 1 where fragments pass
    BlendMode blend = BlendMode::Replace;
    VkPipelineLayout layout = VK_NULL_HANDLE;
};

// Creates the pipeline (the caller keeps and destroys the shader modules). `what` names it in
// the error, e.g. `creating the "composite" pipeline failed (VkResult -3)`.
Result<VkPipeline> create_graphics_pipeline(VkDevice device, VkPipelineCache cache,
                                            const GraphicsPipelineDesc& desc, const char* what);

}  // namespace acetate
