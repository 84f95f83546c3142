// Load time of an effect instance: what the plugin is told about its floor (ABI 1.0 and 1.1
// fields), its build(), and what its declarations need on the GPU (textures, targets in their
// formats, compiled passes, uniforms, floor data, lights). Nothing here runs per frame.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "render/effect_pipelines.hpp"
#include "render/effect_runtime.hpp"
#include "render/floor_facts.hpp"
#include "render/renderer.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {
namespace {

// Why the device cannot render to and sample `format` (or blend onto it); "" when it can.
std::string format_problem(VulkanContext& context, VkFormat floor_format, uint32_t format,
                           bool blend) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(context.physical_device(),
                                        target_vk_format(format, floor_format), &properties);
    VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT |
                                  VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                  VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    if (blend) needed |= VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT;
    if ((properties.optimalTilingFeatures & needed) == needed) return "";
    return fmt::format("cannot be {} on device \"{}\"",
                       blend ? "blended onto" : "rendered to and sampled linearly",
                       context.device_name());
}

}  // namespace

VkFormat target_vk_format(uint32_t format, VkFormat floor_format) {
    switch (format) {
        case ACETATE_FORMAT_R16F:
            return VK_FORMAT_R16_SFLOAT;
        case ACETATE_FORMAT_RG16F:
            return VK_FORMAT_R16G16_SFLOAT;
        case ACETATE_FORMAT_RGBA16F:
            return VK_FORMAT_R16G16B16A16_SFLOAT;
        case ACETATE_FORMAT_R32F:
            return VK_FORMAT_R32_SFLOAT;
        case ACETATE_FORMAT_RG32F:
            return VK_FORMAT_R32G32_SFLOAT;
        case ACETATE_FORMAT_RGBA32F:
            return VK_FORMAT_R32G32B32A32_SFLOAT;
        default:
            return floor_format;
    }
}

PixelRect floor_coverage_bounds(const SceneDesc& scene, size_t floor) {
    PixelRect bounds;
    for (const TileDesc& t : scene.floors.at(floor).tiles)
        bounds = bounding_union(bounds, pixels_covered(t.rect.x, t.rect.y, t.rect.width,
                                                       t.rect.height, scene.width, scene.height));
    return bounds;
}

namespace {

ViewTransform view_of(const InstanceSetup& setup, const SceneDesc& scene) {
    return setup.view.width ? setup.view : ViewTransform::whole(scene.width, scene.height);
}

// The effect entry an error of its instance concerns (Error::file, field, plugin, floor), where
// the error does not say more precisely already.
Error concerning(Error error, const SceneDesc& scene, const EffectRef& ref, int64_t floor) {
    if (error.file.empty()) error.file = scene.file.string();
    if (error.field.empty()) error.field = ref.where;
    if (error.plugin.empty()) error.plugin = ref.plugin;
    if (floor >= 0 && !error.floor) error.floor = uint32_t(floor);
    return error;
}

Result<PreparedInstance> prepare(Renderer& renderer, const SceneDesc& scene, const EffectRef& ref,
                                 int64_t floor, const InstanceSetup& setup) {
    VulkanContext& context = renderer.context();
    const std::string file = scene.file.string();
    auto plugin = renderer.plugins().load(ref.plugin);
    if (!plugin)
        return make_error(plugin.error().code, fmt::format("{}: {}.plugin: {}", file, ref.where,
                                                           plugin.error().message));
    const EffectDescriptor& d = plugin.value()->descriptor;
    const uint32_t wanted = floor < 0 ? ACETATE_SCOPE_GLOBAL : ACETATE_SCOPE_FLOOR;
    if (d.scope != wanted)
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{}: {}.plugin: \"{}\" is a {} effect; list it in {}", file, ref.where,
                        d.id, d.scope == ACETATE_SCOPE_GLOBAL ? "global" : "floor",
                        d.scope == ACETATE_SCOPE_GLOBAL ? "global_effects" : "a floor's effects"));
    auto params = resolve_param_vectors(d, ref, file);
    if (!params) return params.error();

    PreparedInstance out;
    out.instance = std::make_unique<EffectInstance>();
    EffectInstance& instance = *out.instance;
    instance.plugin = plugin.value();
    instance.floor = floor;
    instance.expanding = d.coverage == ACETATE_COVERAGE_EXPANDING;
    instance.params = params.value();
    instance.label = fmt::format(
        "{}.{}", floor < 0 ? std::string("global") : fmt::format("floor{}", floor), d.id);

    FloorFacts facts;
    describe_floor(scene, floor, d, instance.params, view_of(setup, scene), facts);
    GraphContext graph_context;
    graph_context.masks = setup.masks;
    graph_context.canvas_width = scene.width;
    graph_context.canvas_height = scene.height;
    graph_context.format_problem = [&](uint32_t format, bool blend) {
        return format_problem(context, setup.format, format, blend);
    };
    auto graph = build_effect_graph(*instance.plugin, facts.info, instance.label, graph_context);
    if (!graph)
        return make_error(graph.error().code,
                          fmt::format("{}: {}: {}", file, ref.where, graph.error().message));
    for (const std::string& line : graph->log)
        std::fprintf(stderr, "acetate: log: %s\n", line.c_str());
    instance.reach = graph->reach;
    for (const GraphPhase& phase : graph->phases) instance.phase_periods.push_back(phase.period);
    instance.frame_layout = EffectFrameLayout(instance.params.size(), graph->phases.size());
    instance.graph_digest = effect_graph_digest(graph.value());
    out.graph = std::move(graph.value());
    out.lights = std::move(facts.light_infos);
    return out;
}

Result<std::unique_ptr<EffectInstance>> create(Renderer& renderer, const SceneDesc& scene,
                                               const EffectRef& ref, const InstanceSetup& setup,
                                               PreparedInstance* prepared) {
    VulkanContext& context = renderer.context();
    const std::string file = scene.file.string();
    std::unique_ptr<EffectInstance> instance = std::move(prepared->instance);
    const EffectGraph* graph = &prepared->graph;
    const EffectDescriptor& d = instance->plugin->descriptor;

    for (const GraphTexture& t : graph->textures) {
        auto image =
            GpuImage::create(context, fmt::format("{}.{}", instance->label, t.name), t.width,
                             t.height, target_vk_format(t.format, setup.format),
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, false);
        if (!image) return image.error();
        ACETATE_TRY(upload_texels(context, image.value(), t.texels.data(), t.channels));
        instance->textures.emplace(t.name, std::move(image.value()));
    }
    std::map<std::string, VkFormat> output_formats{{"result", setup.format}};
    for (const GraphTarget& t : graph->targets) {
        const VkFormat format = target_vk_format(t.format, setup.format);
        const ViewTransform view = view_of(setup, scene);
        auto image = setup.targets->get(context, d.id, t, view.width, view.height, format);
        if (!image) return image.error();
        instance->targets[t.name] = image.value();
        output_formats[t.name] = format;
    }
    EffectPipelines& pipelines = renderer.effect_pipelines();
    for (const GraphPass& pass : graph->passes) {
        EffectPassRuntime runtime;
        runtime.label = instance->label + "." + pass.name;
        for (const std::string& input : pass.inputs) {
            PassInput resolved;
            if (input.rfind("texture.", 0) == 0)
                resolved.image = &instance->textures.at(input.substr(8));
            else if (input.rfind("mask.", 0) == 0)
                resolved.mask_kind = input.substr(5);
            else if (input != "previous")
                resolved.image = instance->targets.at(input);
            runtime.inputs.push_back(std::move(resolved));
        }
        runtime.target = pass.output == "result" ? nullptr : instance->targets.at(pass.output);
        runtime.blend = pass.blend;
        runtime.instance_count = pass.instance_count;
        runtime.instance_data_offset = pass.instance_data_offset;
        std::shared_ptr<const std::vector<uint32_t>> spirv;
        runtime.from_glsl = !pass.glsl.empty();
        if (runtime.from_glsl) {
            // The pool keys SPIR-V by the whole source, preamble included, and pipelines by the
            // SPIR-V, so checked and unchecked variants never share a shader or a pipeline.
            const std::string source =
                effect_glsl_preamble(d, pass, graph->phases, setup.checked_builtins) + pass.glsl;
            auto compiled = renderer.pool().spirv(runtime.label, ShaderStage::Fragment, source);
            if (!compiled)
                return make_error(
                    compiled.error().code,
                    fmt::format("{}: {}: {} ({})", file, ref.where, compiled.error().message,
                                instance->plugin->file.string()));
            spirv = compiled.value();
        } else {
            spirv = std::make_shared<const std::vector<uint32_t>>(pass.spirv);
        }
        auto pipeline =
            pipelines.pipeline(*spirv, output_formats.at(pass.output), pass.blend, pass.kind);
        if (!pipeline)
            return make_error(pipeline.error().code,
                              fmt::format("{}: {}: pass \"{}\": {}", file, ref.where, runtime.label,
                                          pipeline.error().message));
        runtime.pipeline = pipeline.value();
        auto uniforms = GpuBuffer::create(
            context, instance->frame_layout.bytes(),
            // binding 0 for SPIR-V modules, kFrameStorageBinding for GLSL
            VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        if (!uniforms) return uniforms.error();
        runtime.uniforms = std::move(uniforms.value());
        std::memset(runtime.uniforms.mapped(), 0, runtime.uniforms.size());
        instance->passes.push_back(std::move(runtime));
    }
    if (!graph->floor_data.empty()) {
        auto buffer = GpuBuffer::create(context, graph->floor_data.size() * sizeof(float),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        if (!buffer) return buffer.error();
        std::memcpy(buffer->mapped(), graph->floor_data.data(),
                    graph->floor_data.size() * sizeof(float));
        instance->floor_data = std::move(buffer.value());
        instance->has_floor_data = true;
    }
    count_instanced_pixels(*instance, view_of(setup, scene));
    if (!prepared->lights.empty()) {
        std::vector<EffectLightGpu> lights;
        for (const AcetateLightInfo& l : prepared->lights)
            lights.push_back({{l.pos[0], l.pos[1]},
                              l.height,
                              l.radius,
                              {l.color[0], l.color[1], l.color[2]},
                              l.intensity,
                              {l.direction[0], l.direction[1], l.direction[2]},
                              l.kind});
        auto buffer = GpuBuffer::create(context, lights.size() * sizeof(EffectLightGpu),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        if (!buffer) return buffer.error();
        std::memcpy(buffer->mapped(), lights.data(), lights.size() * sizeof(EffectLightGpu));
        instance->lights = std::move(buffer.value());
        instance->has_lights = true;
    }
    return instance;
}

}  // namespace

Result<PreparedInstance> prepare_effect_instance(Renderer& renderer, const SceneDesc& scene,
                                                 const EffectRef& ref, int64_t floor,
                                                 const InstanceSetup& setup) {
    auto prepared = prepare(renderer, scene, ref, floor, setup);
    if (!prepared) return concerning(prepared.error(), scene, ref, floor);
    return prepared;
}

Result<std::unique_ptr<EffectInstance>> create_effect_instance(Renderer& renderer,
                                                               const SceneDesc& scene,
                                                               const EffectRef& ref, int64_t floor,
                                                               const InstanceSetup& setup) {
    auto prepared = prepare(renderer, scene, ref, floor, setup);
    if (!prepared) return concerning(prepared.error(), scene, ref, floor);
    return create_effect_instance(renderer, scene, ref, floor, setup, std::move(prepared.value()));
}

Result<std::unique_ptr<EffectInstance>> create_effect_instance(Renderer& renderer,
                                                               const SceneDesc& scene,
                                                               const EffectRef& ref, int64_t floor,
                                                               const InstanceSetup& setup,
                                                               PreparedInstance prepared) {
    auto created = create(renderer, scene, ref, setup, &prepared);
    if (!created) return concerning(created.error(), scene, ref, floor);
    return created;
}

}  // namespace acetate
