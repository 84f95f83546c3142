#include "render/host_pipelines.hpp"

#include <fmt/format.h>

#include <string_view>

#include "core/check.hpp"
#include "render/pipeline_pool.hpp"
#include "vulkan/graphics_pipeline.hpp"
#include "vulkan/shader_compiler.hpp"
#include "vulkan/vk_check.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {

const char* host_pass_name(HostPass stage) {
    switch (stage) {
        case HostPass::TileToTarget:
            return "tile-to-target";
        case HostPass::TileToAccum:
            return "tile-to-accumulation";
        case HostPass::Composite:
            return "composite";
        case HostPass::CompositeByAlpha:
            return "composite-by-alpha";
        case HostPass::InjectCovered:
            return "inject-covered";
        case HostPass::InjectUncovered:
            return "inject-uncovered";
        case HostPass::Output:
            return "output";
        case HostPass::TileToTargetIsolation:
            return "tile-to-target-isolation";
        case HostPass::TileToAccumIsolation:
            return "tile-to-accumulation-isolation";
        case HostPass::MaskView:
            return "mask-view";
        case HostPass::Count:
            break;
    }
    return "?";
}

HostPass view_variant(HostPass stage, bool isolation) {
    if (!isolation) return stage;
    if (stage == HostPass::TileToTarget) return HostPass::TileToTargetIsolation;
    if (stage == HostPass::TileToAccum) return HostPass::TileToAccumIsolation;
    return stage;
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

StageState state_of(HostPass stage) {
    switch (stage) {
        case HostPass::TileToTarget:
        case HostPass::TileToTargetIsolation:
            return {"tile.vert", "tile.frag", true, VK_COMPARE_OP_ALWAYS, true, true};
        case HostPass::TileToAccum:
        case HostPass::TileToAccumIsolation:
            return {"tile.vert", "tile.frag", false, VK_COMPARE_OP_ALWAYS, false, true};
        case HostPass::Composite:
            return {"fullscreen.vert", "composite.frag", true, VK_COMPARE_OP_EQUAL, false, true};
        case HostPass::CompositeByAlpha:
            return {"fullscreen.vert", "composite.frag", true, VK_COMPARE_OP_ALWAYS, false, true};
        case HostPass::InjectCovered:
            return {"fullscreen.vert", "inject.frag", true, VK_COMPARE_OP_EQUAL, false, false};
        case HostPass::InjectUncovered:
            return {"fullscreen.vert", "inject.frag", true, VK_COMPARE_OP_NOT_EQUAL, false, false};
        case HostPass::MaskView:
            return {"fullscreen.vert", "mask_view.frag", false, VK_COMPARE_OP_ALWAYS, false, false};
        default:
            return {"fullscreen.vert", "output.frag", false, VK_COMPARE_OP_ALWAYS, false, false};
    }
}

// The variants of tile.frag and composite.frag (see their headers), inserted after the
// #version line: each is a shader of its own.
const char* defines_of(HostPass stage) {
    switch (stage) {
        case HostPass::CompositeByAlpha:
            return "#define GATE_BY_ALPHA\n";
        case HostPass::TileToTarget:
            return "#define KEEP_COVERAGE\n";
        case HostPass::TileToTargetIsolation:
            return "#define KEEP_COVERAGE\n#define ISOLATION\n";
        case HostPass::TileToAccumIsolation:
            return "#define ISOLATION\n";
        default:
            return "";
    }
}

}  // namespace

Result<std::unique_ptr<HostPipelines>> HostPipelines::create(VulkanContext& context,
                                                             PipelinePool& pool) {
    std::unique_ptr<HostPipelines> out(new HostPipelines(context, pool));
    ACETATE_TRY(out->create_layout());
    return out;
}

Result<void> HostPipelines::ensure(HostPass stage, VkFormat color_format) {
    if (pipelines_.count({stage, color_format})) return {};
    const std::string key = fmt::format("host/{}/{}", host_pass_name(stage), int(color_format));
    auto pipeline = pool_.pipeline(
        key, [&](VkPipelineCache cache) { return create_pass(stage, color_format, cache); });
    if (!pipeline) return pipeline.error();
    pipelines_[{stage, color_format}] = pipeline.value();
    return {};
}

VkPipeline HostPipelines::pipeline(HostPass stage, VkFormat color_format) const {
    const auto found = pipelines_.find({stage, color_format});
    ACETATE_CHECK(found != pipelines_.end(), "stage \"%s\" was not prepared at load",
                  host_pass_name(stage));
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
                              kHostPushConstantBytes};
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

Result<VkPipeline> HostPipelines::create_pass(HostPass stage, VkFormat color_format,
                                              VkPipelineCache cache) {
    const StageState s = state_of(stage);
    auto compile = [&](const char* name, std::string_view defines) -> Result<VkShaderModule> {
        const std::string_view n(name);
        std::string source(embedded_shader(name));
        // GLSL wants #version first; the defines go right after it. The pool keys SPIR-V by
        // the whole source, so each variant compiles once and apart from the others.
        if (!defines.empty()) source.insert(source.find('\n') + 1, defines);
        auto spirv = pool_.spirv(
            name, n.ends_with(".vert") ? ShaderStage::Vertex : ShaderStage::Fragment, source);
        if (!spirv) return spirv.error();
        return pool_.module(*spirv.value());
    };
    auto vert = compile(s.vertex, "");
    if (!vert) return vert.error();
    auto frag = compile(s.fragment, defines_of(stage));
    if (!frag) {
        vkDestroyShaderModule(context_.device(), vert.value(), nullptr);
        return frag.error();
    }

    GraphicsPipelineDesc desc;
    desc.vertex = vert.value();
    desc.fragment = frag.value();
    const bool is_tile = std::string_view(s.vertex) == "tile.vert";
    desc.topology =
        is_tile ? VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    desc.color_format = color_format;
    if (s.stencil_attachment) desc.stencil_format = context_.stencil_format();
    desc.stencil_test = s.stencil_attachment;
    desc.stencil_compare = s.stencil_compare;
    desc.stencil_write = s.stencil_write;
    // Premultiplied "over" for every stage that composites (docs/design.md, L-one-alpha).
    desc.blend = s.over_blend ? BlendMode::Over : BlendMode::Replace;
    desc.layout = layout_;
    auto pipeline = create_graphics_pipeline(context_.device(), cache, desc, host_pass_name(stage));
    vkDestroyShaderModule(context_.device(), vert.value(), nullptr);
    vkDestroyShaderModule(context_.device(), frag.value(), nullptr);
    return pipeline;
}

}  // namespace acetate
