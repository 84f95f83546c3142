#include "render/compositor.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstring>

#include "render/compositor_internal.hpp"
#include "render/renderer.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {
namespace {

using namespace compositor_detail;

// Fills `area` of `image` with `colour` (a render pass that only clears: loadOp CLEAR limited to
// the render area, which vkCmdClearColorImage cannot limit). Leaves it a colour attachment.
void fill_area(VkCommandBuffer cmd, GpuImage& image, const PixelRect& area,
               const std::array<float, 4>& colour) {
    if (area.empty()) return;
    image.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    VkRenderingAttachmentInfo attachment = color_attachment(image.view(), true);
    std::memcpy(attachment.clearValue.color.float32, colour.data(), sizeof(float) * 4);
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = to_vk(area);
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &attachment;
    vkCmdBeginRendering(cmd, &info);
    vkCmdEndRendering(cmd);
}

FloorFrameReport frame_report(const FloorStep& step) {
    FloorFrameReport report;
    report.floor = step.floor;
    report.path = to_string(step.path);
    report.why = step.why;
    report.scissor = step.scissor;
    return report;
}

}  // namespace

Result<OutputView> parse_view(const std::string& name) {
    for (int v = 0; v <= int(OutputView::Isolation); ++v)
        if (name == to_string(OutputView(v))) return OutputView(v);
    return make_error(ErrorCode::InvalidInput,
                      fmt::format("--view: unknown view \"{}\"; expected normal, floor-alpha, "
                                  "accum-alpha, floor-rgb, violations or isolation",
                                  name));
}

const char* to_string(OutputView view) {
    switch (view) {
        case OutputView::Normal:
            return "normal";
        case OutputView::FloorAlpha:
            return "floor-alpha";
        case OutputView::AccumAlpha:
            return "accum-alpha";
        case OutputView::FloorRgb:
            return "floor-rgb";
        case OutputView::Violations:
            return "violations";
        case OutputView::Isolation:
            return "isolation";
    }
    return "?";
}

bool view_reads_floor_target(OutputView view) {
    return view == OutputView::FloorAlpha || view == OutputView::FloorRgb ||
           view == OutputView::Violations;
}

std::array<float, 3> isolation_tint(uint32_t index) {
    // Hues spaced by the golden angle so neighbouring floors never look alike.
    const float hue = std::fmod(index * 0.381966f, 1.0f) * 6.0f;
    const float x = 1.0f - std::fabs(std::fmod(hue, 2.0f) - 1.0f);
    const int sector = int(hue);
    const std::array<std::array<float, 3>, 6> rgb = {
        {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}}};
    return rgb[size_t(sector % 6)];
}

Compositor::Compositor(Renderer& renderer) : renderer_(renderer), context_(renderer.context()) {}

VkPipeline Compositor::host_pipeline(HostPass stage) const {
    return pipelines_->pipeline(stage, options_.format);
}

Compositor::~Compositor() {
    if (context_.device()) vkDeviceWaitIdle(context_.device());
}

HostPass Compositor::inject_stage() const {
    return options_.inject && options_.inject->inside_coverage ? HostPass::InjectCovered
                                                               : HostPass::InjectUncovered;
}

void Compositor::set_scissor(VkCommandBuffer cmd, const PixelRect& rect) {
    VkViewport viewport{0, 0, float(width_), float(height_), 0, 1};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    VkRect2D scissor = to_vk(rect);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void Compositor::bind(VkCommandBuffer cmd, HostPass stage, VkImageView primary,
                      VkImageView secondary, VkSampler sampler) {
    // Tile stages draw with their isolation variant in that view (the one load prepared).
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                      host_pipeline(view_variant(stage, options_.view == OutputView::Isolation)));
    VkDescriptorImageInfo images[2] = {
        {sampler, primary, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        {sampler, secondary, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
    VkDescriptorBufferInfo buffer{violations_.buffer(), 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet writes[3] = {};
    for (uint32_t i = 0; i < 3; ++i) {
        writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType =
            i < 2 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        if (i < 2)
            writes[i].pImageInfo = &images[i];
        else
            writes[i].pBufferInfo = &buffer;
    }
    context_.push_descriptor_fn()(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_->layout(), 0, 3,
                                  writes);
}

void Compositor::draw_tiles(VkCommandBuffer cmd, HostPass stage, uint32_t floor,
                            const PixelRect& scissor, FloorFrameReport& report) {
    const LoadedFloor& loaded = resources_->floors()[floor];
    const auto tint = isolation_tint(floor);
    set_scissor(cmd, scissor);
    for (const LoadedTile& tile : loaded.tiles) {
        const PixelRect shaded = intersect(tile.pixels, scissor);
        if (shaded.empty()) continue;
        bind(cmd, stage, tile.texture->view(), tile.texture->view(),
             pipelines_->tile_sampler(tile.one_to_one));
        HostPassPushConstants push;
        push.rect[0] = float(tile.rect.x);
        push.rect[1] = float(tile.rect.y);
        push.rect[2] = float(tile.rect.width);
        push.rect[3] = float(tile.rect.height);
        push.tint[0] = tint[0];
        push.tint[1] = tint[1];
        push.tint[2] = tint[2];
        push.canvas[0] = float(width_);
        push.canvas[1] = float(height_);
        push.floor_index = floor;
        vkCmdPushConstants(cmd, pipelines_->layout(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        vkCmdDraw(cmd, 4, 1, 0, 0);
        ++report.passes;
        report.pixels_shaded += shaded.area();
    }
}

void Compositor::record_floors_direct(VkCommandBuffer cmd, const std::vector<FloorStep>& steps,
                                      size_t first, size_t end, FrameStats& stats) {
    // Consecutive floors drawn directly share one rendering pass over the union of their
    // scissors: blending happens in draw order within a pass, so this is the same "over" as one
    // pass per floor, without the barrier and the pass set-up between floors. Each floor's
    // draws keep their own scissor.
    PixelRect area;
    for (size_t i = first; i < end; ++i)
        if (steps[i].path == FloorPath::Direct) area = bounding_union(area, steps[i].scissor);
    accumulation_.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    VkRenderingAttachmentInfo color = color_attachment(accumulation_.view(), false);
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = to_vk(area);
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    vkCmdBeginRendering(cmd, &info);
    for (size_t i = first; i < end; ++i) {
        const FloorStep& step = steps[i];
        FloorFrameReport report = frame_report(step);
        // Over is associative, so drawing each tile over the accumulation equals compositing
        // the floor's own "tiles over transparent" image over it (docs/OVERVIEW.md).
        if (step.path == FloorPath::Direct)
            draw_tiles(cmd, HostPass::TileToAccum, step.floor, step.scissor, report);
        stats.passes += report.passes;
        stats.pixels_shaded += report.pixels_shaded;
        stats.floors.push_back(report);
    }
    vkCmdEndRendering(cmd);
    if (timer_)
        timer_->mark(cmd, first + 1 == end ? fmt::format("floor {} tiles", steps[first].floor)
                                           : fmt::format("floors {}-{} tiles (one pass)",
                                                         steps[first].floor, steps[end - 1].floor));
}

void Compositor::record_floor_through_target(VkCommandBuffer cmd, const FloorStep& step,
                                             bool clear_all, double time,
                                             FloorFrameReport& report) {
    GpuImage& color = *floor_color_;
    const auto& effects = floor_effects_[step.floor];
    const bool expanding =
        std::any_of(effects.begin(), effects.end(), [](const auto& e) { return e->expanding; });
    // Where the effects' "result" passes and the composite draw: the tiles' union as rects
    // (shading_rects_), unless the plan scissors to the whole canvas.
    const std::vector<PixelRect>* rects =
        !expanding && options_.plan.scissor_to_coverage && !shading_rects_[step.floor].empty()
            ? &shading_rects_[step.floor]
            : nullptr;
    // Effects may sample around a pixel, so with effects the whole target starts transparent:
    // nothing another floor left in it can be read.
    clear_all = clear_all || !effects.empty();
    GpuImage& stencil = *floor_stencil_;
    const bool has_depth = context_.stencil_format() != VK_FORMAT_S8_UINT;
    color.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    stencil.transition(cmd, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);

    VkRenderingAttachmentInfo color_info = color_attachment(color.view(), true);
    VkRenderingAttachmentInfo stencil_info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    stencil_info.imageView = stencil.view();
    stencil_info.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    stencil_info.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    stencil_info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    stencil_info.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    // The clear covers the render area only; debug views read the whole target, so then the
    // whole target is cleared.
    info.renderArea =
        to_vk(clear_all ? PixelRect{0, 0, int64_t(width_), int64_t(height_)} : step.scissor);
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color_info;
    info.pStencilAttachment = &stencil_info;
    info.pDepthAttachment = has_depth ? &stencil_info : nullptr;
    vkCmdBeginRendering(cmd, &info);
    draw_tiles(cmd, HostPass::TileToTarget, step.floor, step.scissor, report);
    if (options_.inject) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, host_pipeline(inject_stage()));
        HostPassPushConstants push;
        std::memcpy(push.tint, options_.inject->colour.data(), sizeof(push.tint));
        vkCmdPushConstants(cmd, pipelines_->layout(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        set_scissor(cmd, step.scissor);  // like any pass: inside the render area
        vkCmdDraw(cmd, 3, 1, 0, 0);
        ++report.passes;
        report.pixels_shaded += step.scissor.area();
    }
    vkCmdEndRendering(cmd);
    color.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    if (timer_) timer_->mark(cmd, fmt::format("floor {} tiles", step.floor));

    // The floor's effects, in scene order, ping-ponging between the two floor targets.
    GpuImage* current = &color;
    if (!effects.empty() && effects_enabled_) {
        GpuImage& other = *floor_pingpong_;
        other.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, other.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1,
                             &range);
        GpuImage* next = &other;
        for (const auto& effect : effects) {
            EffectIo io;
            io.previous = current;
            io.result = next;
            io.result_scissor =
                effect->expanding || expanding ? expansion_areas_[step.floor] : step.scissor;
            io.result_rects = rects;
            io.time = time;
            io.canvas_width = width_;
            io.canvas_height = height_;
            io.timer = timer_.get();
            // What "result" holds before this effect writes it: the poison where its passes
            // shade, the zeros (or tiles) of today elsewhere.
            if (options_.poison) {
                if (rects)
                    for (const PixelRect& r : *rects) fill_area(cmd, *next, r, *options_.poison);
                else
                    fill_area(cmd, *next, io.result_scissor, *options_.poison);
            }
            record_effect(cmd, renderer_, *effect, io, report);
            std::swap(current, next);
        }
    }
    viewed_floor_ = current;

    // Composite: the floor over the accumulation, only where the floor's stencil says 1 (or,
    // after a coverage-expanding effect, wherever the floor is not fully transparent).
    const PixelRect composite_area = expanding ? expansion_areas_[step.floor] : step.scissor;
    accumulation_.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    // Same layout, but the tile pass's stencil writes must be visible to the composite's load.
    stencil.transition(cmd, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    VkRenderingAttachmentInfo accum_info = color_attachment(accumulation_.view(), false);
    stencil_info.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    stencil_info.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
    info.renderArea = to_vk(composite_area);
    info.pColorAttachments = &accum_info;
    vkCmdBeginRendering(cmd, &info);
    set_scissor(cmd, composite_area);
    bind(cmd, expanding ? HostPass::CompositeByAlpha : HostPass::Composite, current->view(),
         current->view(), pipelines_->nearest_sampler());
    HostPassPushConstants push;
    push.floor_index = step.floor;
    push.mode = expanding ? 1u : 0u;
    vkCmdPushConstants(cmd, pipelines_->layout(),
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                       &push);
    uint64_t composited = composite_area.area();
    if (rects) {
        composited = 0;
        for (const PixelRect& r : *rects) {
            set_scissor(cmd, r);
            vkCmdDraw(cmd, 3, 1, 0, 0);
            composited += r.area();
        }
    } else {
        vkCmdDraw(cmd, 3, 1, 0, 0);
    }
    vkCmdEndRendering(cmd);
    if (timer_) timer_->mark(cmd, fmt::format("floor {} composite", step.floor));
    ++report.passes;
    report.pixels_shaded += composited;
}

void Compositor::record_global_effects(VkCommandBuffer cmd, FrameStats& stats, double time) {
    final_accumulation_ = &accumulation_;
    if (global_effects_.empty() || !global_effects_enabled_) return;
    GpuImage* current = &accumulation_;
    GpuImage* next = &*accumulation_pingpong_;
    // Like the floor ping-pong: "result" starts transparent every frame.
    next->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, next->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1,
                         &range);
    FloorFrameReport report;
    report.floor = UINT32_MAX;
    report.path = "global";
    report.why = "global effects on the composite";
    report.scissor = {0, 0, int64_t(width_), int64_t(height_)};
    for (const auto& effect : global_effects_) {
        EffectIo io;
        io.previous = current;
        io.result = next;
        io.result_scissor = report.scissor;  // every pass writes every pixel of "result"
        io.time = time;
        io.canvas_width = width_;
        io.canvas_height = height_;
        io.timer = timer_.get();
        if (options_.poison) fill_area(cmd, *next, io.result_scissor, *options_.poison);
        record_effect(cmd, renderer_, *effect, io, report);
        std::swap(current, next);
    }
    final_accumulation_ = current;
    stats.passes += report.passes;
    stats.pixels_shaded += report.pixels_shaded;
    stats.global = report;
}

void Compositor::record_output(VkCommandBuffer cmd, FrameStats& stats) {
    GpuImage& accumulation = final_accumulation_ ? *final_accumulation_ : accumulation_;
    GpuImage* floor_image =
        viewed_floor_ ? viewed_floor_ : (floor_color_ ? &*floor_color_ : nullptr);
    accumulation.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const bool floor_view = view_reads_floor_target(options_.view) && floor_image;
    if (floor_view) floor_image->transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    output_.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    const PixelRect all{0, 0, int64_t(width_), int64_t(height_)};
    VkRenderingAttachmentInfo color = color_attachment(output_.view(), false);
    color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // every pixel is written
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = to_vk(all);
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    vkCmdBeginRendering(cmd, &info);
    set_scissor(cmd, all);
    bind(cmd, HostPass::Output, accumulation.view(),
         floor_view ? floor_image->view() : accumulation.view(), pipelines_->nearest_sampler());
    HostPassPushConstants push;
    std::memcpy(push.tint, scene_.background.data(), sizeof(push.tint));
    push.canvas[0] = float(width_);
    push.canvas[1] = float(height_);
    push.floor_index = uint32_t(options_.view);
    vkCmdPushConstants(cmd, pipelines_->layout(),
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                       &push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    if (timer_) timer_->mark(cmd, "output");
    ++stats.passes;
    stats.pixels_shaded += all.area();
}

void Compositor::record_frame(VkCommandBuffer cmd, const FramePlan& plan, FrameStats& stats,
                              double time) {
    viewed_floor_ = floor_color_ ? &*floor_color_ : nullptr;
    if (timer_) timer_->begin(cmd);
    accumulation_.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, accumulation_.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1,
                         &range);
    if (timer_) timer_->mark(cmd, "clear");
    const bool floor_view = view_reads_floor_target(options_.view);
    const std::vector<FloorStep>& steps = plan.steps;
    for (size_t i = 0; i < steps.size();) {
        if (steps[i].path == FloorPath::Direct) {
            // The run of floors up to the next one with a target (skipped floors record
            // nothing, so they do not break it).
            size_t end = i + 1;
            while (options_.plan.merge_direct_floors && end < steps.size() &&
                   steps[end].path != FloorPath::ThroughTarget)
                ++end;
            record_floors_direct(cmd, steps, i, end, stats);
            i = end;
            continue;
        }
        const FloorStep& step = steps[i++];
        FloorFrameReport report = frame_report(step);
        if (step.path == FloorPath::ThroughTarget) {
            const bool is_viewed = floor_view && step.floor == stats.active_floor;
            record_floor_through_target(cmd, step, is_viewed, time, report);
        }
        stats.passes += report.passes;
        stats.pixels_shaded += report.pixels_shaded;
        stats.floors.push_back(report);
    }
    if (floor_view && plan.steps.back().path != FloorPath::ThroughTarget) {
        // The active floor drew nothing (it covers no pixel), so its target must read as empty,
        // not as whatever a lower floor left in the shared target.
        floor_color_->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdClearColorImage(cmd, floor_color_->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             &zero, 1, &range);
        viewed_floor_ = &*floor_color_;
    }
    record_global_effects(cmd, stats, time);
    record_output(cmd, stats);
}

Result<FrameStats> Compositor::render(uint32_t active_floor, double time) {
    if (active_floor >= floor_count())
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{}: active floor {} does not exist (the scene has {} "
                        "floors, 0..{})",
                        scene_.file.string(), active_floor, floor_count(), floor_count() - 1));
    if (view_reads_floor_target(options_.view) && !floor_color_)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("view \"{}\" needs a floor target; load the scene with it",
                                      to_string(options_.view)));
    const auto start = std::chrono::steady_clock::now();
    const ResourceCounters before = context_.counters();
    PlanOptions plan_options = options_.plan;
    if (view_reads_floor_target(options_.view)) plan_options.force_target_floor = active_floor;
    if (options_.inject) plan_options.draw_direct = false;  // the hook acts like an effect
    last_plan_ = plan_frame(width_, height_, geometry_, active_floor, plan_options);

    FrameStats stats;
    stats.active_floor = active_floor;
    std::memset(violations_.mapped(), 0, violations_.size());
    ACETATE_TRY(context_.submit_and_wait(
        [&](VkCommandBuffer cmd) { record_frame(cmd, last_plan_, stats, time); }));
    stats.milliseconds = milliseconds_since(start);
    if (timer_) {
        auto timings = timer_->read();
        if (!timings) return timings.error();
        stats.gpu_passes = std::move(timings.value());
    }

    const auto* counts = static_cast<const uint32_t*>(violations_.mapped());
    for (FloorFrameReport& f : stats.floors) {
        f.violations = counts[f.floor];
        stats.violations += f.violations;
    }
    const ResourceCounters used = delta(context_.counters(), before);
    stats.images_loaded = used.images_loaded;
    stats.targets_allocated = used.targets_allocated;
    stats.shaders_compiled = used.shaders_compiled;
    stats.pipelines_created = used.pipelines_created;
    return stats;
}

Result<ImageRGBA> Compositor::read_output() {
    return read_back_image(context_, output_);
}
Result<ImageRGBA> Compositor::read_accumulation() {
    return read_back_image(context_, final_accumulation_ ? *final_accumulation_ : accumulation_);
}

Result<ImageRGBA> Compositor::read_active_floor() {
    if (!view_reads_floor_target(options_.view) || !viewed_floor_)
        return make_error(ErrorCode::InvalidInput,
                          "read_active_floor needs a view that reads the floor target "
                          "(floor-rgb, floor-alpha or violations)");
    return read_back_image(context_, *viewed_floor_);
}

EffectPassCounts Compositor::effect_pass_counts() const {
    EffectPassCounts counts;
    auto add = [&](const EffectInstance& effect) {
        for (const EffectPassRuntime& pass : effect.passes)
            ++(pass.from_glsl ? counts.glsl : counts.spirv);
    };
    for (const auto& floor : floor_effects_)
        for (const auto& effect : floor) add(*effect);
    for (const auto& effect : global_effects_) add(*effect);
    return counts;
}

std::vector<TargetInfo> Compositor::targets_held() const {
    std::vector<TargetInfo> out;
    auto add = [&](const GpuImage& image) {
        out.push_back({image.name(), format_name(image.format()), image.width(), image.height(),
                       image.bytes()});
    };
    add(accumulation_);
    add(output_);
    if (accumulation_pingpong_) add(*accumulation_pingpong_);
    if (floor_color_) add(*floor_color_);
    if (floor_stencil_) add(*floor_stencil_);
    if (floor_pingpong_) add(*floor_pingpong_);
    for (const GpuImage* image : effect_targets_.images()) add(*image);
    return out;
}

std::vector<TargetInfo> Compositor::images_held() const {
    std::vector<TargetInfo> out = targets_held();
    for (const GpuImage* image : resources_->images())
        out.push_back({image->name(), format_name(image->format()), image->width(), image->height(),
                       image->bytes()});
    return out;
}

}  // namespace acetate
