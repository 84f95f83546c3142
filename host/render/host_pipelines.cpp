#include "render/host_pipelines.hpp"

#include <fmt/format.h>

#include "core/check.hpp"
#include "render/pipeline_pool.hpp"
#include "vulkan/shader_compiler.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {

const char* stage_name(Stage stage) {
    switch (stage) {
        case Stage::TileToTarget: return "tile-to-target";
        case Stage::TileToAccum: return "tile-to-accumulation";
        case Stage::Composite: return "composite";
        case Stage::CompositeByAlpha: return "composite-by-alpha";
        case Stage::InjectCovered: return "inject-covered";
        case Stage::InjectUncovered: return "inject-uncovered";
        case Stage::Output: return "output";
        case Stage::Count: break;
    }
    return "?";
}

namespace {

struct StageState {
    const char* vertex;
    const char* fragment;
    bool stencil_attachment;
    VkCompareOp stencil_compare;
    bool stencil_write;
    bool over_blend;
};

StageState state_of(Stage stage) {
    switch (stage) {
        case Stage::TileToTarget:
            return {"tile.vert", "tile.frag", true, VK_COMPARE_OP_ALWAYS, true, true};
        case Stage::TileToAccum:
            return {"tile.vert", "tile.frag", false, VK_COMPARE_OP_ALWAYS, false, true};
        case Stage::Composite:
            return {"fullscreen.vert", "composite.frag", true, VK_COMPARE_OP_EQUAL, false, true};
        case Stage::CompositeByAlpha:
            return {"fullscreen.vert", "composite.frag", true, VK_COMPARE_OP_ALWAYS, false, true};
        case Stage::InjectCovered:
            return {"fullscreen.vert", "inject.frag", true, VK_COMPARE_OP_EQUAL, false, false};
        case Stage::InjectUncovered:
            return {"fullscreen.vert", "inject.frag", true, VK_COMPARE_OP_NOT_EQUAL, false, false};
        default:
            return {"fullscreen.vert", "output.frag", false, VK_COMPARE_OP_ALWAYS, false, false};
    }
}

}  // namespace

Result<std::unique_ptr<HostPipelines>> HostPipelines::create(VulkanContext& context,
                                                             PipelinePool& pool) {
    std::unique_ptr<HostPipelines> out(new HostPipelines(context, pool));
    ACETATE_TRY(out->create_layout());
    return out;
}

Result<void> HostPipelines::ensure(Stage stage, VkFormat color_format) {
    if (pipelines_.count({stage, color_format})) return {};
    const std::string key = fmt::format("host/{}/{}", stage_name(stage), int(color_format));
    auto pipeline = pool_.pipeline(
        key, [&](VkPipelineCache cache) { return create_stage(stage, color_format, cache); });
    if (!pipeline) return pipeline.error();
    pipelines_[{stage, color_format}] = pipeline.value();
    return {};
}

VkPipeline HostPipelines::pipeline(Stage stage, VkFormat color_format) const {
    const auto found = pipelines_.find({stage, color_format});
    ACETATE_CHECK(found != pipelines_.end(), "stage \"%s\" was not prepared at load",
                  stage_name(stage));
    return found->second;
}

HostPipelines::~HostPipelines() {
    VkDevice device = context_.device();
    if (layout_) vkDestroyPipelineLayout(device, layout_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
    if (linear_sampler_) vkDestroySampler(device, linear_sampler_, nullptr);
    if (nearest_sampler_) vkDestroySampler(device, nearest_sampler_, nullptr);
}

Result<void> HostPipelines::create_layout() {
    VkDevice device = context_.device();
    VkDescriptorSetLayoutBinding bindings[3] = {};
    for (uint32_t i = 0; i < 2; ++i) {
        bindings[i].binding = i;
        bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        bindings[i].descriptorCount = 1;
        bindings[i].stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
    }
    bindings[2].binding = kViolationBuffer;
    bindings[2].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[2].descriptorCount = 1;
    bindings[2].stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    set_info.bindingCount = 3;
    set_info.pBindings = bindings;
    ACETATE_VK(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &set_layout_));

    VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                              sizeof(StagePushConstants)};
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout_;
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &range;
    ACETATE_VK(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout_));

    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler.magFilter = sampler.minFilter = VK_FILTER_LINEAR;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW =
        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler.maxLod = 0.0f;
    ACETATE_VK(vkCreateSampler(device, &sampler, nullptr, &linear_sampler_));
    sampler.magFilter = sampler.minFilter = VK_FILTER_NEAREST;
    ACETATE_VK(vkCreateSampler(device, &sampler, nullptr, &nearest_sampler_));
    return {};
}

Result<VkPipeline> HostPipelines::create_stage(Stage stage, VkFormat color_format,
                                               VkPipelineCache cache) {
    const StageState s = state_of(stage);
    auto compile = [&](const char* name) -> Result<VkShaderModule> {
        const std::string_view n(name);
        auto spirv = pool_.spirv(name, n.ends_with(".vert") ? ShaderStage::Vertex
                                                            : ShaderStage::Fragment,
                                 embedded_shader(name));
        if (!spirv) return spirv.error();
        return pool_.module(*spirv.value());
    };
    auto vert = compile(s.vertex);
    if (!vert) return vert.error();
    auto frag = compile(s.fragment);
    if (!frag) {
        vkDestroyShaderModule(context_.device(), vert.value(), nullptr);
        return frag.error();
    }

    VkPipelineShaderStageCreateInfo stages[2] = {};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
                 VK_SHADER_STAGE_VERTEX_BIT, vert.value(), "main", nullptr};
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
                 VK_SHADER_STAGE_FRAGMENT_BIT, frag.value(), "main", nullptr};

    VkPipelineVertexInputStateCreateInfo vertex_input{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    const bool is_tile = stage == Stage::TileToTarget || stage == Stage::TileToAccum;
    assembly.topology =
        is_tile ? VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

    VkPipelineDepthStencilStateCreateInfo depth_stencil{
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth_stencil.stencilTestEnable = s.stencil_attachment ? VK_TRUE : VK_FALSE;
    VkStencilOpState op{};
    op.failOp = VK_STENCIL_OP_KEEP;
    op.passOp = s.stencil_write ? VK_STENCIL_OP_REPLACE : VK_STENCIL_OP_KEEP;
    op.depthFailOp = VK_STENCIL_OP_KEEP;
    op.compareOp = s.stencil_compare;
    op.compareMask = 0xff;
    op.writeMask = s.stencil_write ? 0xff : 0x00;
    op.reference = 1;  // "this floor covers here"
    depth_stencil.front = depth_stencil.back = op;

    VkPipelineColorBlendAttachmentState blend{};
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                           VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    if (s.over_blend) {
        // Premultiplied "over": out = src + dst * (1 - src.a), for colour and alpha alike.
        blend.blendEnable = VK_TRUE;
        blend.srcColorBlendFactor = blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blend.dstColorBlendFactor = blend.dstAlphaBlendFactor =
            VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    VkPipelineColorBlendStateCreateInfo blend_state{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend_state.attachmentCount = 1;
    blend_state.pAttachments = &blend;

    const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic_state{
        VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic_state.dynamicStateCount = 2;
    dynamic_state.pDynamicStates = dynamic;

    const VkFormat stencil = context_.stencil_format();
    const bool has_depth = stencil != VK_FORMAT_S8_UINT;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &color_format;
    if (s.stencil_attachment) {
        rendering.stencilAttachmentFormat = stencil;
        rendering.depthAttachmentFormat = has_depth ? stencil : VK_FORMAT_UNDEFINED;
    }

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth_stencil;
    info.pColorBlendState = &blend_state;
    info.pDynamicState = &dynamic_state;
    info.layout = layout_;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkResult r = vkCreateGraphicsPipelines(context_.device(), cache, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(context_.device(), vert.value(), nullptr);
    vkDestroyShaderModule(context_.device(), frag.value(), nullptr);
    if (r != VK_SUCCESS)
        return make_error(ErrorCode::VulkanCall,
                          fmt::format("creating the \"{}\" pipeline failed (VkResult {})",
                                      stage_name(stage), int(r)),
                          r);
    return pipeline;
}

}  // namespace acetate
