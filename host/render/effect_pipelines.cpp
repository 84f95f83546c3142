#include "render/effect_pipelines.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "core/sha256.hpp"
#include "render/effect_frame_layout.hpp"
#include "render/pipeline_pool.hpp"
#include "vulkan/graphics_pipeline.hpp"
#include "vulkan/vk_check.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {

std::string checked_builtins_glsl() {
    // The helpers are defined before the #defines, so inside them min, max, clamp and
    // smoothstep are still the built-ins. The NaN test compares bits: isnan() survives
    // lavapipe, but a compiler that may assume no NaN (Vulkan lets it, without
    // SignedZeroInfNanPreserve) can fold isnan() to false, and never an integer comparison.
    std::string out =
        "float acetate_nan() { return uintBitsToFloat(0x7fc00000u); }\n"
        "bool acetate_isnan(float x) {\n"
        "    return (floatBitsToUint(x) & 0x7fffffffu) > 0x7f800000u;\n}\n";
    for (int n = 2; n <= 4; ++n)
        out += fmt::format(
            "bvec{0} acetate_isnan(vec{0} x) {{\n"
            "    return greaterThan(floatBitsToUint(x) & uvec{0}(0x7fffffffu), "
            "uvec{0}(0x7f800000u));\n}}\n",
            n);
    const char* floats[] = {"float", "vec2", "vec3", "vec4"};
    for (const char* t : floats) {
        const bool scalar = std::strcmp(t, "float") == 0;
        out += fmt::format(
            "{0} acetate_nan_where({0} v, {0} operand) {{\n"
            "    return mix(v, {0}(acetate_nan()), acetate_isnan(operand));\n}}\n"
            "{0} acetate_checked_min({0} a, {0} b) {{\n"
            "    return acetate_nan_where(acetate_nan_where(min(a, b), a), b);\n}}\n"
            "{0} acetate_checked_max({0} a, {0} b) {{\n"
            "    return acetate_nan_where(acetate_nan_where(max(a, b), a), b);\n}}\n"
            "{0} acetate_checked_clamp({0} x, {0} lo, {0} hi) {{\n"
            "    return acetate_nan_where(acetate_nan_where(acetate_nan_where(clamp(x, lo, hi), "
            "x), lo), hi);\n}}\n"
            "{0} acetate_checked_smoothstep({0} e0, {0} e1, {0} x) {{\n"
            "    {0} r = acetate_nan_where(acetate_nan_where(acetate_nan_where("
            "smoothstep(e0, e1, x), e0), e1), x);\n"
            "    return mix(r, {0}(acetate_nan()), {1});\n}}\n",
            t, scalar ? "e0 >= e1" : "greaterThanEqual(e0, e1)");
        if (scalar) continue;
        // The forms with a float operand: the same as that float in every component.
        out += fmt::format(
            "{0} acetate_checked_min({0} a, float b) {{ return acetate_checked_min(a, {0}(b)); "
            "}}\n"
            "{0} acetate_checked_max({0} a, float b) {{ return acetate_checked_max(a, {0}(b)); "
            "}}\n"
            "{0} acetate_checked_clamp({0} x, float lo, float hi) {{\n"
            "    return acetate_checked_clamp(x, {0}(lo), {0}(hi));\n}}\n"
            "{0} acetate_checked_smoothstep(float e0, float e1, {0} x) {{\n"
            "    return acetate_checked_smoothstep({0}(e0), {0}(e1), x);\n}}\n",
            t);
    }
    // Integer forms have no NaN: they forward, so integer min, max and clamp still compile.
    const char* integers[][2] = {{"int", "int"},    {"ivec2", "int"}, {"ivec3", "int"},
                                 {"ivec4", "int"},  {"uint", "uint"}, {"uvec2", "uint"},
                                 {"uvec3", "uint"}, {"uvec4", "uint"}};
    for (const auto& [t, scalar] : integers) {
        std::vector<std::string> operands{t};
        if (std::strcmp(t, scalar) != 0) operands.push_back(scalar);
        for (const std::string& o : operands)
            out += fmt::format(
                "{0} acetate_checked_min({0} a, {1} b) {{ return min(a, b); }}\n"
                "{0} acetate_checked_max({0} a, {1} b) {{ return max(a, b); }}\n"
                "{0} acetate_checked_clamp({0} x, {1} lo, {1} hi) {{ return clamp(x, lo, hi); "
                "}}\n",
                t, o);
    }
    // texelFetch outside the texture (or its mip levels) is undefined: lavapipe reads zeros,
    // which look like a transparent border, another driver may read anything. Checked, it
    // reads NaN. Every input a pass names is a float sampler2D.
    out +=
        "vec4 acetate_checked_texelFetch(sampler2D s, ivec2 p, int lod) {\n"
        "    if (lod < 0 || lod >= textureQueryLevels(s)) return vec4(acetate_nan());\n"
        "    ivec2 size = textureSize(s, lod);\n"
        "    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size)))\n"
        "        return vec4(acetate_nan());\n"
        "    return texelFetch(s, p, lod);\n}\n";
    out +=
        "#define texelFetch(s, p, lod) acetate_checked_texelFetch(s, p, lod)\n"
        "#define min(a, b) acetate_checked_min(a, b)\n"
        "#define max(a, b) acetate_checked_max(a, b)\n"
        "#define clamp(x, lo, hi) acetate_checked_clamp(x, lo, hi)\n"
        "#define smoothstep(e0, e1, x) acetate_checked_smoothstep(e0, e1, x)\n";
    return out;
}

std::string effect_glsl_preamble(const EffectDescriptor& effect, const GraphPass& pass,
                                 const std::vector<GraphPhase>& phases, bool checked_builtins,
                                 FrameBlockDeclaration frame) {
    // The frame block (EffectFrameLayout). Both declarations have the same std140 layout; see
    // kFrameStorageBinding for why GLSL passes get storage.
    std::string out = "#version 450\n";
    out +=
        frame == FrameBlockDeclaration::Storage
            ? fmt::format("layout(set = 0, binding = {}, std140) readonly buffer AcetateFrame {{\n",
                          EffectPipelines::kFrameStorageBinding)
            : fmt::format("layout(set = 0, binding = {}, std140) uniform AcetateFrame {{\n",
                          EffectPipelines::kFrameBinding);
    out += EffectFrameLayout(effect.params.size(), phases.size()).glsl_members() + "};\n";
    // ABI 1.2: the camera (EffectViewPushConstants) and the two conversions a pass needs.
    out +=
        "layout(push_constant) uniform AcetateView {\n"
        "    vec4 acetate_view;          // origin x, y (scene pixels), scale, 1/scale\n"
        "    vec4 acetate_scene_canvas;  // the scene's canvas: width, height, 1/width, 1/height\n"
        "};\n"
        "#define acetate_view_origin (acetate_view.xy)\n"
        "#define acetate_view_scale (acetate_view.z)\n"
        "vec2 acetate_scene_position(vec2 render_pixel) {\n"
        "    return acetate_view.xy + render_pixel * acetate_view.w;\n}\n"
        "vec2 acetate_render_position(vec2 scene_position) {\n"
        "    return (scene_position - acetate_view.xy) * acetate_view.z;\n}\n";
    out +=
        "#define acetate_time (acetate_misc.x)\n#define acetate_floor (int(acetate_misc.y))\n"
        "#define acetate_time_whole (acetate_clock.x)\n"
        "#define acetate_time_fraction (acetate_clock.y)\n";
    for (size_t i = 0; i < effect.params.size(); ++i) {
        const uint32_t n = effect.params[i].components();
        out += fmt::format("#define param_{} (acetate_params[{}].{})\n", effect.params[i].name, i,
                           n == 1   ? "x"
                           : n == 2 ? "xy"
                                    : "xyz");
    }
    for (size_t i = 0; i < phases.size(); ++i)
        out += fmt::format("#define phase_{} (acetate_phases[{}].x)\n", phases[i].name, i);
    for (size_t i = 0; i < pass.inputs.size(); ++i) {
        const std::string& name =
            i < pass.input_names.size() ? pass.input_names[i] : input_variable(pass.inputs[i]);
        out += fmt::format("layout(set = 0, binding = {}) uniform sampler2D {};\n",
                           EffectPipelines::kFirstInputBinding + i, name);
        out += fmt::format(
            "#define acetate_size_{0} (vec4(vec2(textureSize({0}, 0)), "
            "1.0 / vec2(textureSize({0}, 0))))\n",
            name);
    }
    out += fmt::format(
        "layout(set = 0, binding = {}, std430) readonly buffer AcetateFloorData {{ float "
        "floor_data[]; }};\n",
        EffectPipelines::kFloorDataBinding);
    out += fmt::format(
        "struct AcetateLight {{ vec2 position; float height; float radius; vec3 color; "
        "float intensity; vec3 direction; uint kind; }};\n"
        "layout(set = 0, binding = {}, std430) readonly buffer AcetateLights {{ AcetateLight "
        "acetate_lights[]; }};\n"
        "#define acetate_light_count (acetate_lights.length())\n"
        "#define ACETATE_LIGHT_POINT 0u\n#define ACETATE_LIGHT_SUN 1u\n",
        EffectPipelines::kLightsBinding);
    if (pass.kind == ACETATE_PASS_INSTANCED_QUADS)
        out +=
            "layout(location = 0) in vec2 acetate_uv;\n"
            "layout(location = 1) flat in int acetate_instance;\n";
    out += "layout(location = 0) out vec4 out_color;\n";
    if (checked_builtins) out += checked_builtins_glsl();
    out += pass.defines;
    out += "#line 1\n";  // last: compiler messages give lines in the plugin's own text
    return out;
}

std::string effect_glsl_preamble(const EffectDescriptor& effect,
                                 const std::vector<std::string>& inputs, uint32_t kind,
                                 bool checked_builtins, FrameBlockDeclaration frame) {
    GraphPass pass;
    pass.inputs = inputs;
    pass.kind = kind;
    return effect_glsl_preamble(effect, pass, {}, checked_builtins, frame);
}

Result<std::unique_ptr<EffectPipelines>> EffectPipelines::create(VulkanContext& context,
                                                                 PipelinePool& pool) {
    std::unique_ptr<EffectPipelines> out(new EffectPipelines(context, pool));
    VkDevice device = context.device();
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    // The frame block and floor_data are read by the instanced-quad vertex shader too.
    const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    bindings.push_back({kFrameBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, both, nullptr});
    for (uint32_t i = 0; i < kMaxInputs; ++i)
        bindings.push_back({kFirstInputBinding + i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                            VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    bindings.push_back({kFloorDataBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, both, nullptr});
    bindings.push_back({kLightsBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                        VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    bindings.push_back({kFrameStorageBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, both, nullptr});
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    set_info.bindingCount = uint32_t(bindings.size());
    set_info.pBindings = bindings.data();
    ACETATE_VK(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &out->set_layout_));
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &out->set_layout_;
    const VkPushConstantRange view_range{both, 0, sizeof(EffectViewPushConstants)};
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &view_range;
    ACETATE_VK(vkCreatePipelineLayout(device, &layout_info, nullptr, &out->layout_));

    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler.magFilter = sampler.minFilter = VK_FILTER_LINEAR;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW =
        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    ACETATE_VK(vkCreateSampler(device, &sampler, nullptr, &out->sampler_));

    auto blank =
        GpuImage::create(context, "effect.blank", 1, 1, VK_FORMAT_R16G16B16A16_SFLOAT,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, false);
    if (!blank) return blank.error();
    out->blank_ = std::move(blank.value());
    ACETATE_TRY(upload_image(context, out->blank_, ImageRGBA(1, 1)));
    auto buffer = GpuBuffer::create(context, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!buffer) return buffer.error();
    out->empty_buffer_ = std::move(buffer.value());
    std::memset(out->empty_buffer_.mapped(), 0, 16);
    return out;
}

EffectPipelines::~EffectPipelines() {
    VkDevice device = context_.device();
    if (sampler_) vkDestroySampler(device, sampler_, nullptr);
    if (layout_) vkDestroyPipelineLayout(device, layout_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
}

Result<VkPipeline> EffectPipelines::pipeline(const std::vector<uint32_t>& fragment_spirv,
                                             VkFormat format, uint32_t blend, uint32_t kind) {
    const bool instanced = kind == ACETATE_PASS_INSTANCED_QUADS;
    const std::string key =
        fmt::format("effect/{}/{}/{}/{}",
                    sha256_hex(fragment_spirv.data(), fragment_spirv.size() * sizeof(uint32_t)),
                    int(format), blend, kind);
    return pool_.pipeline(key, [&](VkPipelineCache cache) -> Result<VkPipeline> {
        const char* vertex_name = instanced ? "instanced_quad.vert" : "fullscreen.vert";
        auto vertex_spirv =
            pool_.spirv(vertex_name, ShaderStage::Vertex, embedded_shader(vertex_name));
        if (!vertex_spirv) return vertex_spirv.error();
        auto vert = pool_.module(*vertex_spirv.value());
        if (!vert) return vert.error();
        auto frag = pool_.module(fragment_spirv);
        if (!frag) {
            vkDestroyShaderModule(context_.device(), vert.value(), nullptr);
            return frag.error();
        }
        GraphicsPipelineDesc desc;
        desc.vertex = vert.value();
        desc.fragment = frag.value();
        desc.topology =
            instanced ? VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        desc.color_format = format;
        desc.blend = blend == ACETATE_BLEND_ADD    ? BlendMode::Add
                     : blend == ACETATE_BLEND_OVER ? BlendMode::Over
                                                   : BlendMode::Replace;
        desc.layout = layout_;
        auto pipeline = create_graphics_pipeline(context_.device(), cache, desc, "effect pass");
        vkDestroyShaderModule(context_.device(), vert.value(), nullptr);
        vkDestroyShaderModule(context_.device(), frag.value(), nullptr);
        return pipeline;
    });
}

}  // namespace acetate
