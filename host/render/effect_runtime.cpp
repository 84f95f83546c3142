#include "render/effect_runtime.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "render/effect_pipelines.hpp"
#include "render/renderer.hpp"
#include "vulkan/render_commands.hpp"
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
    const std::string key =
        fmt::format("{}.{}/{}/{}", plugin_id, target.name, target.divisor, int(format));
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

void bind_pass_masks(EffectInstance& instance, const std::map<std::string, GpuImage>* masks,
                     const GpuImage& blank) {
    for (EffectPassRuntime& pass : instance.passes)
        for (PassInput& input : pass.inputs) {
            if (input.mask_kind.empty()) continue;
            input.image = &blank;
            if (masks)
                if (auto found = masks->find(input.mask_kind); found != masks->end())
                    input.image = &found->second;
        }
}

void count_instanced_pixels(EffectInstance& instance, const ViewTransform& view) {
    const auto* data =
        instance.has_floor_data ? static_cast<const float*>(instance.floor_data.mapped()) : nullptr;
    for (EffectPassRuntime& pass : instance.passes) {
        pass.instanced_pixels = 0;
        for (uint32_t i = 0; data && i < pass.instance_count; ++i) {
            const float* r = &data[pass.instance_data_offset + 4 * i];
            pass.instanced_pixels += view.covered(r[0], r[1], r[2], r[3]).area();
        }
    }
}

const GpuImage* effect_pass_input(const EffectPassRuntime& pass, size_t binding,
                                  const EffectIo& io) {
    return pass.inputs[binding].image ? pass.inputs[binding].image : io.previous;
}

GpuImage* effect_pass_output(const EffectPassRuntime& pass, const EffectIo& io) {
    return pass.target ? pass.target : io.result;
}

void record_effect_pass(VkCommandBuffer cmd, Renderer& renderer, EffectInstance& instance,
                        size_t index, const EffectIo& io, FloorFrameReport& report) {
    EffectPipelines& pipelines = renderer.effect_pipelines();
    VulkanContext& context = renderer.context();
    EffectPassRuntime& pass = instance.passes[index];
    GpuImage* output = effect_pass_output(pass, io);
    PixelRect scissor = pass.target
                            ? PixelRect{0, 0, int64_t(output->width()), int64_t(output->height())}
                            : io.result_scissor;
    if (io.warm_up) scissor = PixelRect{0, 0, 1, 1};
    // Frame uniforms for this pass (the buffer is host-coherent and frames are synchronous).
    auto* u = static_cast<float*>(pass.uniforms.mapped());
    const EffectFrameLayout& layout = instance.frame_layout;
    const float w = float(io.canvas_width), h = float(io.canvas_height);
    const float ow = float(output->width()), oh = float(output->height());
    const float canvas[4] = {w, h, 1 / w, 1 / h}, out[4] = {ow, oh, 1 / ow, 1 / oh};
    const float misc[4] = {float(io.time), float(instance.floor), float(pass.instance_data_offset),
                           0};
    std::memcpy(u + layout.canvas(), canvas, sizeof(canvas));
    std::memcpy(u + layout.output(), out, sizeof(out));
    std::memcpy(u + layout.misc(), misc, sizeof(misc));
    for (size_t i = 0; i < instance.params.size(); ++i)
        std::memcpy(u + layout.param(i), instance.params[i].data(), 4 * sizeof(float));
    // The clock and phases are reduced in double here, so a shader at 10^5 s animates as
    // smoothly as at 1 s (acetate_time, a float, steps by 7.8 ms there).
    float* clock = u + layout.clock();
    const double whole = std::floor(io.time);
    clock[0] = float(std::fmod(whole, 16777216.0));  // exact in a float up to 2^24 s
    // Kept below 1 as the phases are: a time just under a whole second (2.99999999) has a
    // fraction that rounds to 1.0f, which an effect reading it as [0, 1) must never see.
    clock[1] = std::min(float(io.time - whole), 0x1.fffffep-1f);
    for (size_t i = 0; i < instance.phase_periods.size(); ++i) {
        double turns = io.time / instance.phase_periods[i];
        if (!std::isfinite(turns)) turns = 0;  // a time no frame reaches; never a NaN phase
        // fract() of a float that rounds up to 1.0 would wrap a whole turn early.
        u[layout.phase(i)] = std::min(float(turns - std::floor(turns)), 0x1.fffffep-1f);
    }

    // Inputs in binding order; the bindings past them read the blank texture.
    std::array<VkDescriptorImageInfo, EffectPipelines::kMaxInputs> images;
    for (size_t i = 0; i < images.size(); ++i) {
        const GpuImage* image =
            i >= pass.inputs.size() ? &pipelines.blank_texture() : effect_pass_input(pass, i, io);
        images[i] = {pipelines.sampler(), image->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    }
    begin_rendering(cmd, scissor, {output, LoadOp::Keep});
    set_viewport_and_scissor(cmd, output->width(), output->height(), scissor);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pass.pipeline);
    const EffectViewPushConstants view{
        {float(io.view.x), float(io.view.y), float(io.view.scale), float(1 / io.view.scale)},
        {float(io.scene_width), float(io.scene_height), 1.0f / float(io.scene_width),
         1.0f / float(io.scene_height)}};
    vkCmdPushConstants(cmd, pipelines.layout(),
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(view),
                       &view);

    VkDescriptorBufferInfo frame{pass.uniforms.buffer(), 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo data{
        instance.has_floor_data ? instance.floor_data.buffer() : pipelines.empty_buffer().buffer(),
        0, VK_WHOLE_SIZE};
    // The frame uniforms (twice), every input binding, the floor data and the lights.
    std::array<VkWriteDescriptorSet, EffectPipelines::kMaxInputs + 4> writes{};
    size_t count = 0;
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.descriptorCount = 1;
    write.dstBinding = EffectPipelines::kFrameBinding;
    write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    write.pBufferInfo = &frame;
    writes[count++] = write;
    write.dstBinding = EffectPipelines::kFrameStorageBinding;  // the same bytes, for GLSL
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[count++] = write;
    for (uint32_t i = 0; i < EffectPipelines::kMaxInputs; ++i) {
        write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.descriptorCount = 1;
        write.dstBinding = EffectPipelines::kFirstInputBinding + i;
        write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        write.pImageInfo = &images[i];
        writes[count++] = write;
    }
    write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.descriptorCount = 1;
    write.dstBinding = EffectPipelines::kFloorDataBinding;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &data;
    writes[count++] = write;
    VkDescriptorBufferInfo lights{
        instance.has_lights ? instance.lights.buffer() : pipelines.empty_buffer().buffer(), 0,
        VK_WHOLE_SIZE};
    write.dstBinding = EffectPipelines::kLightsBinding;
    write.pBufferInfo = &lights;
    writes[count++] = write;
    context.push_descriptor_fn()(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.layout(), 0,
                                 uint32_t(count), writes.data());
    // A "result" pass over a floor whose tiles lie apart draws once per rect of their
    // union, so the gaps in their bounding box are never shaded.
    const bool per_rect = !pass.target && !pass.instance_count && io.result_rects && !io.warm_up;
    uint64_t rect_pixels = 0;
    if (pass.instance_count) {
        vkCmdDraw(cmd, 4, io.warm_up ? 1 : pass.instance_count, 0, 0);
    } else if (per_rect) {
        for (const PixelRect& r : *io.result_rects) {
            const VkRect2D rect = to_vk(r);
            vkCmdSetScissor(cmd, 0, 1, &rect);
            vkCmdDraw(cmd, 3, 1, 0, 0);
            rect_pixels += r.area();
        }
    } else {
        vkCmdDraw(cmd, 3, 1, 0, 0);
    }
    vkCmdEndRendering(cmd);
    if (io.timer) io.timer->mark(cmd, pass.label);
    ++report.passes;
    // An instanced pass shades its quads (clipped to the canvas; overlaps count twice).
    report.pixels_shaded += pass.instance_count ? pass.instanced_pixels
                            : per_rect          ? rect_pixels
                                                : scissor.area();
}

}  // namespace acetate
