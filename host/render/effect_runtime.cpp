#include "render/effect_runtime.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "render/effect_pipelines.hpp"
#include "render/renderer.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {
namespace {

uint32_t divided(uint32_t size, uint32_t divisor) {
    return std::max(1u, (size + divisor - 1) / divisor);
}

}  // namespace

Result<GpuImage*> EffectTargets::get(VulkanContext& context, const std::string& plugin_id,
                                     const GraphTarget& target, uint32_t canvas_width,
                                     uint32_t canvas_height, VkFormat format) {
    const std::string key = fmt::format("{}.{}/{}", plugin_id, target.name, target.divisor);
    if (auto found = images_.find(key); found != images_.end()) return found->second.get();
    auto image = GpuImage::create(
        context, fmt::format("{}.{}", plugin_id, target.name),
        divided(canvas_width, target.divisor), divided(canvas_height, target.divisor), format,
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
            VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
        true);
    if (!image) return image.error();
    auto owned = std::make_unique<GpuImage>(std::move(image.value()));
    GpuImage* raw = owned.get();
    images_.emplace(key, std::move(owned));
    return raw;
}

std::vector<const GpuImage*> EffectTargets::images() const {
    std::vector<const GpuImage*> out;
    for (const auto& [key, image] : images_) out.push_back(image.get());
    return out;
}

std::vector<GpuImage*> EffectTargets::images() {
    std::vector<GpuImage*> out;
    for (const auto& [key, image] : images_) out.push_back(image.get());
    return out;
}

Result<std::vector<float>> resolve_params(const EffectDescriptor& d, const EffectRef& ref,
                                          const std::string& scene_file) {
    std::vector<float> values;
    for (const EffectParam& p : d.params) values.push_back(p.default_value);
    auto set = [&](const std::string& name, float value) {
        const EffectParam& p = d.params[size_t(d.param_index(name))];
        if (p.type == ACETATE_PARAM_INT) value = std::round(value);
        if (p.type == ACETATE_PARAM_BOOL) value = value >= 0.5f ? 1.0f : 0.0f;
        values[size_t(d.param_index(name))] = std::clamp(value, p.min_value, p.max_value);
    };
    if (!ref.preset.empty()) {
        const auto preset = d.presets.find(ref.preset);
        if (preset == d.presets.end()) {
            std::string known;
            for (const auto& [name, unused] : d.presets)
                known += (known.empty() ? "" : ", ") + name;
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: {}.preset: plugin \"{}\" has no preset \"{}\" "
                                          "(it has: {})",
                                          scene_file, ref.where, d.id, ref.preset,
                                          known.empty() ? "none" : known));
        }
        for (const auto& [name, value] : preset->second) set(name, value);
    }
    for (const auto& [name, value] : ref.params.items()) {
        if (d.param_index(name) < 0) {
            std::string known;
            for (const EffectParam& p : d.params) known += (known.empty() ? "" : ", ") + p.name;
            return make_error(
                ErrorCode::InvalidInput,
                fmt::format("{}: {}.params.{}: plugin \"{}\" has no such parameter "
                            "(it has: {})",
                            scene_file, ref.where, name, d.id, known.empty() ? "none" : known));
        }
        if (!value.is_number() && !value.is_boolean())
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: {}.params.{}: expected a number, got {}", scene_file,
                                          ref.where, name, value.dump()));
        // Read as double first: a value beyond the float range (-1e308) is out of range, not
        // "not finite" as it would look after the conversion.
        const double wide =
            value.is_boolean() ? (value.get<bool>() ? 1.0 : 0.0) : value.get<double>();
        if (!std::isfinite(wide))
            return make_error(
                ErrorCode::InvalidInput,
                fmt::format("{}: {}.params.{}: not a finite number", scene_file, ref.where, name));
        if (std::abs(wide) > double(std::numeric_limits<float>::max()))
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: {}.params.{}: {} is out of range for a 32-bit float",
                                          scene_file, ref.where, name, value.dump()));
        const float number = float(wide);
        set(name, number);
    }
    return values;
}

Result<std::unique_ptr<EffectInstance>> create_effect_instance(
    Renderer& renderer, const SceneDesc& scene, const EffectRef& ref, int64_t floor,
    VkFormat format, EffectTargets& targets, bool checked_builtins) {
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
    auto params = resolve_params(d, ref, file);
    if (!params) return params.error();

    auto instance = std::make_unique<EffectInstance>();
    instance->plugin = plugin.value();
    instance->floor = floor;
    instance->expanding = d.coverage == ACETATE_COVERAGE_EXPANDING;
    instance->params = params.value();
    instance->label = fmt::format(
        "{}.{}", floor < 0 ? std::string("global") : fmt::format("floor{}", floor), d.id);

    // What the plugin is told about its floor.
    std::vector<AcetateLight> lights;
    std::vector<const char*> masks_present;
    std::string floor_name;
    if (floor >= 0) {
        const FloorDesc& f = scene.floors[size_t(floor)];
        floor_name = f.name;
        for (const LightDesc& l : f.lights)
            lights.push_back({{l.pos[0], l.pos[1]},
                              l.radius,
                              {l.color[0], l.color[1], l.color[2]},
                              l.intensity});
        for (const std::string& kind : d.masks)
            if (std::any_of(f.tiles.begin(), f.tiles.end(),
                            [&](const TileDesc& t) { return t.masks.count(kind) != 0; }))
                masks_present.push_back(kind.c_str());
    }
    AcetateFloorInfo info{};
    info.struct_size = sizeof(info);
    info.floor_index = floor < 0 ? UINT32_MAX : uint32_t(floor);
    info.floor_name = floor_name.c_str();
    info.canvas_width = scene.width;
    info.canvas_height = scene.height;
    info.lights = lights.empty() ? nullptr : lights.data();
    info.light_count = uint32_t(lights.size());
    info.params = instance->params.data();
    info.param_count = uint32_t(instance->params.size());
    info.masks_present = masks_present.empty() ? nullptr : masks_present.data();
    info.masks_present_count = uint32_t(masks_present.size());

    auto graph = build_effect_graph(*instance->plugin, info, instance->label);
    if (!graph)
        return make_error(graph.error().code,
                          fmt::format("{}: {}: {}", file, ref.where, graph.error().message));

    for (const std::string& line : graph->log)
        std::fprintf(stderr, "acetate: log: %s\n", line.c_str());
    for (const GraphTexture& t : graph->textures) {
        auto image = GpuImage::create(
            context, fmt::format("{}.{}", instance->label, t.name), t.width, t.height, format,
            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, false);
        if (!image) return image.error();
        ImageRGBA pixels(t.width, t.height);
        pixels.pixels = t.rgba;
        ACETATE_TRY(upload_image(context, image.value(), pixels));
        instance->textures.emplace(t.name, std::move(image.value()));
    }
    for (const GraphTarget& t : graph->targets) {
        auto image = targets.get(context, d.id, t, scene.width, scene.height, format);
        if (!image) return image.error();
        instance->targets[t.name] = image.value();
    }
    EffectPipelines& pipelines = renderer.effect_pipelines();
    for (const GraphPass& pass : graph->passes) {
        EffectPassRuntime runtime;
        runtime.label = instance->label + "." + pass.name;
        runtime.inputs = pass.inputs;
        runtime.output = pass.output;
        runtime.blend = pass.blend;
        runtime.instance_count = pass.instance_count;
        runtime.instance_data_offset = pass.instance_data_offset;
        for (uint32_t i = 0; i < pass.instance_count; ++i) {
            const float* r = &graph->floor_data[pass.instance_data_offset + 4 * i];
            runtime.instanced_pixels +=
                pixels_covered(r[0], r[1], r[2], r[3], scene.width, scene.height).area();
        }
        std::shared_ptr<const std::vector<uint32_t>> spirv;
        runtime.from_glsl = !pass.glsl.empty();
        if (runtime.from_glsl) {
            // The pool keys SPIR-V by the whole source, preamble included, and pipelines by the
            // SPIR-V, so checked and unchecked variants never share a shader or a pipeline.
            const std::string source =
                effect_glsl_preamble(d, pass.inputs, pass.kind, checked_builtins) + pass.glsl;
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
        auto pipeline = pipelines.pipeline(*spirv, format, pass.blend, pass.kind);
        if (!pipeline)
            return make_error(pipeline.error().code,
                              fmt::format("{}: {}: pass \"{}\": {}", file, ref.where, runtime.label,
                                          pipeline.error().message));
        runtime.pipeline = pipeline.value();
        auto uniforms = GpuBuffer::create(
            context, sizeof(EffectFrameUniforms) + 16 * std::max<size_t>(1, d.params.size()),
            VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
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
    return instance;
}

void record_effect(VkCommandBuffer cmd, Renderer& renderer, EffectInstance& instance,
                   const EffectIo& io, FloorFrameReport& report) {
    EffectPipelines& pipelines = renderer.effect_pipelines();
    VulkanContext& context = renderer.context();
    for (EffectPassRuntime& pass : instance.passes) {
        GpuImage* output = pass.output == "result" ? io.result : instance.targets.at(pass.output);
        PixelRect scissor = pass.output == "result" ? io.result_scissor
                                                    : PixelRect{0, 0, int64_t(output->width()),
                                                                int64_t(output->height())};
        if (io.warm_up) scissor = PixelRect{0, 0, 1, 1};
        // Frame uniforms for this pass (the buffer is host-coherent and frames are synchronous).
        auto* u = static_cast<float*>(pass.uniforms.mapped());
        const float w = float(io.canvas_width), h = float(io.canvas_height);
        const float ow = float(output->width()), oh = float(output->height());
        const float header[12] = {w,
                                  h,
                                  1 / w,
                                  1 / h,
                                  ow,
                                  oh,
                                  1 / ow,
                                  1 / oh,
                                  io.time,
                                  float(instance.floor),
                                  float(pass.instance_data_offset),
                                  0};
        std::memcpy(u, header, sizeof(header));
        for (size_t i = 0; i < instance.params.size(); ++i) u[12 + i * 4] = instance.params[i];

        // Inputs in binding order.
        std::vector<VkDescriptorImageInfo> images;
        for (const std::string& input : pass.inputs) {
            const GpuImage* image = nullptr;
            if (input == "previous") {
                image = io.previous;
            } else if (input.rfind("texture.", 0) == 0) {
                image = &instance.textures.at(input.substr(8));
            } else if (input.rfind("mask.", 0) == 0) {
                // A floor without this mask kind reads a transparent texture.
                image = io.blank_mask ? io.blank_mask : &pipelines.blank_texture();
                if (io.masks)
                    if (auto found = io.masks->find(input.substr(5)); found != io.masks->end())
                        image = &found->second;
            } else {
                image = instance.targets.at(input);
            }
            GpuImage* mutable_image = const_cast<GpuImage*>(image);
            if (mutable_image->layout() != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
                mutable_image->transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
            images.push_back(
                {pipelines.sampler(), image->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
        }
        while (images.size() < EffectPipelines::kMaxInputs)
            images.push_back({pipelines.sampler(), pipelines.blank_texture().view(),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
        output->transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);

        VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        color.imageView = output->view();
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{int32_t(scissor.x0), int32_t(scissor.y0)},
                           {uint32_t(scissor.x1 - scissor.x0), uint32_t(scissor.y1 - scissor.y0)}};
        info.layerCount = 1;
        info.colorAttachmentCount = 1;
        info.pColorAttachments = &color;
        vkCmdBeginRendering(cmd, &info);
        VkViewport viewport{0, 0, ow, oh, 0, 1};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &info.renderArea);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pass.pipeline);

        VkDescriptorBufferInfo frame{pass.uniforms.buffer(), 0, VK_WHOLE_SIZE};
        VkDescriptorBufferInfo data{instance.has_floor_data ? instance.floor_data.buffer()
                                                            : pipelines.empty_buffer().buffer(),
                                    0, VK_WHOLE_SIZE};
        std::vector<VkWriteDescriptorSet> writes;
        VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.descriptorCount = 1;
        write.dstBinding = EffectPipelines::kFrameBinding;
        write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        write.pBufferInfo = &frame;
        writes.push_back(write);
        for (uint32_t i = 0; i < EffectPipelines::kMaxInputs; ++i) {
            write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            write.descriptorCount = 1;
            write.dstBinding = EffectPipelines::kFirstInputBinding + i;
            write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            write.pImageInfo = &images[i];
            writes.push_back(write);
        }
        write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.descriptorCount = 1;
        write.dstBinding = EffectPipelines::kFloorDataBinding;
        write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        write.pBufferInfo = &data;
        writes.push_back(write);
        context.push_descriptor_fn()(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.layout(), 0,
                                     uint32_t(writes.size()), writes.data());
        if (pass.instance_count)
            vkCmdDraw(cmd, 4, io.warm_up ? 1 : pass.instance_count, 0, 0);
        else
            vkCmdDraw(cmd, 3, 1, 0, 0);
        vkCmdEndRendering(cmd);
        output->transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        ++report.passes;
        // An instanced pass shades its quads (clipped to the canvas; overlaps count twice).
        report.pixels_shaded += pass.instance_count ? pass.instanced_pixels : scissor.area();
    }
}

}  // namespace acetate
