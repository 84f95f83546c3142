// A frame's commands: each floor up to the active one drawn directly into the accumulation or
// through its own target (tiles with the stencil, effects, composite), then the global effects
// and the output pass. Compositor::render (compositor.cpp) plans the frame and submits this.
#include <fmt/format.h>

#include <algorithm>

#include "render/compositor.hpp"  // the class whose recording half this is
#include "render/renderer.hpp"
#include "vulkan/render_commands.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {
namespace {

FloorFrameReport frame_report(const FloorStep& step) {
    FloorFrameReport report;
    report.floor = step.floor;
    report.path = to_string(step.path);
    report.why = step.why;
    report.scissor = step.scissor;
    return report;
}

}  // namespace

HostPass Compositor::inject_pass() const {
    return options_.inject && options_.inject->inside_coverage ? HostPass::InjectCovered
                                                               : HostPass::InjectUncovered;
}

bool Compositor::expands(uint32_t floor) const {
    const auto& effects = floor_effects_[floor];
    return std::any_of(effects.begin(), effects.end(), [](const auto& e) { return e->expanding; });
}

EffectIo Compositor::effect_io(double time) const {
    EffectIo io;
    io.time = time;
    io.canvas_width = width_;
    io.canvas_height = height_;
    io.view = view_;
    io.scene_width = scene_.width;
    io.scene_height = scene_.height;
    io.timer = timer_.get();
    return io;
}

VkSampler Compositor::tile_sampler(const LoadedTile& tile) const {
    // Texels land on pixels only when the tile is drawn at its own size and the camera keeps
    // whole pixels whole; otherwise the tile is filtered.
    return pipelines_->tile_sampler(tile.one_to_one && view_.pixel_aligned());
}

void Compositor::set_scissor(VkCommandBuffer cmd, const PixelRect& rect) {
    set_viewport_and_scissor(cmd, width_, height_, rect);
}

void Compositor::bind(VkCommandBuffer cmd, HostPass pass, VkImageView primary,
                      VkImageView secondary, VkSampler sampler) {
    // Tile passes draw with their isolation variant in that view (the one load prepared).
    const HostPass drawn = view_variant(pass, options_.view == OutputView::Isolation);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                      pipelines_->pipeline(drawn, options_.format));
    VkDescriptorImageInfo images[2] = {
        {sampler, primary, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        {sampler, secondary, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
    VkDescriptorBufferInfo buffer{targets_.violations().buffer(), 0, VK_WHOLE_SIZE};
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

void Compositor::draw_tiles(VkCommandBuffer cmd, HostPass pass, uint32_t floor,
                            const PixelRect& scissor, FloorFrameReport& report) {
    const LoadedFloor& loaded = resources_->floors()[floor];
    const auto tint = isolation_tint(floor);
    set_scissor(cmd, scissor);
    for (size_t t = 0; t < loaded.tiles.size(); ++t) {
        const LoadedTile& tile = loaded.tiles[t];
        // A tile outside the camera's region (or the scissor) costs nothing.
        const PixelRect shaded = intersect(tile_pixels_[floor][t], scissor);
        if (shaded.empty()) continue;
        bind(cmd, pass, tile.texture->view(), tile.texture->view(), tile_sampler(tile));
        TilePushConstants push;
        push.tile_rect[0] = float(tile.rect.x);
        push.tile_rect[1] = float(tile.rect.y);
        push.tile_rect[2] = float(tile.rect.width);
        push.tile_rect[3] = float(tile.rect.height);
        push.view[0] = float(view_.x), push.view[1] = float(view_.y);
        push.view[2] = float(view_.scale), push.view[3] = float(1 / view_.scale);
        std::copy(tint.begin(), tint.end(), push.isolation_tint);
        push.canvas_size[0] = float(width_);
        push.canvas_size[1] = float(height_);
        pipelines_->push(cmd, push);
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
    begin_rendering(cmd, area, {&targets_.accumulation(), LoadOp::Keep});
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
    GpuImage& colour = *targets_.floor_colour();
    const bool expanding = expands(step.floor);
    // Where the effects' "result" passes and the composite draw: the tiles' union as rects
    // (shading_rects_), unless the plan scissors to the whole canvas.
    const std::vector<PixelRect>* rects =
        !expanding && options_.plan.scissor_to_coverage && !shading_rects_[step.floor].empty()
            ? &shading_rects_[step.floor]
            : nullptr;
    // Effects may sample around a pixel, so with effects the whole target starts transparent:
    // nothing another floor left in it can be read. The clear covers the render area only, and
    // debug views read the whole target, so then the whole target is cleared too.
    clear_all = clear_all || !floor_effects_[step.floor].empty();
    const PixelRect area =
        clear_all ? PixelRect{0, 0, int64_t(width_), int64_t(height_)} : step.scissor;
    const StencilAttachment stencil{targets_.floor_stencil(), LoadOp::Clear, 0, true};
    begin_rendering(cmd, area, {&colour, LoadOp::Clear}, &stencil);
    draw_tiles(cmd, HostPass::TileToTarget, step.floor, step.scissor, report);
    if (options_.inject) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                          pipelines_->pipeline(inject_pass(), options_.format));
        InjectPushConstants push;
        std::copy(options_.inject->colour.begin(), options_.inject->colour.end(), push.colour);
        pipelines_->push(cmd, push);
        set_scissor(cmd, step.scissor);  // like any pass: inside the render area
        vkCmdDraw(cmd, 3, 1, 0, 0);
        ++report.passes;
        report.pixels_shaded += step.scissor.area();
    }
    vkCmdEndRendering(cmd);
    colour.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    if (timer_) timer_->mark(cmd, fmt::format("floor {} tiles", step.floor));

    GpuImage* floor = &colour;
    const auto& effects = floor_effects_[step.floor];
    if (!effects.empty() && effects_enabled_ && floor_effects_run_ > 0) {
        // An expanding effect (or any effect of a floor that has one) writes where the floor's
        // coverage may grow to; the others within the floor's scissor.
        const EffectChain chain{&effects,     std::min<size_t>(effects.size(), floor_effects_run_),
                                &colour,      targets_.floor_pingpong(),
                                step.scissor, expansion_areas_[step.floor],
                                expanding,    rects};
        floor = record_effect_chain(cmd, chain, time, report);
    }
    viewed_floor_ = floor;
    record_composite(cmd, step, *floor, rects, expanding, report);
}

GpuImage* Compositor::record_effect_chain(VkCommandBuffer cmd, const EffectChain& chain,
                                          double time, FloorFrameReport& report) {
    GpuImage* current = chain.current;
    GpuImage* next = chain.next;
    clear_image(cmd, *next);
    for (size_t i = 0; i < chain.run; ++i) {
        EffectInstance& effect = *(*chain.effects)[i];
        EffectIo io = effect_io(time);
        io.previous = current;
        io.result = next;
        io.result_scissor = effect.expanding || chain.expanding ? chain.expanded : chain.scissor;
        io.result_rects = chain.rects;
        // What "result" holds before this effect writes it: the poison where its passes
        // shade, the zeros (or tiles) of today elsewhere.
        if (options_.poison) {
            if (chain.rects)
                for (const PixelRect& r : *chain.rects) fill_area(cmd, *next, r, *options_.poison);
            else
                fill_area(cmd, *next, io.result_scissor, *options_.poison);
        }
        record_effect(cmd, renderer_, effect, io, report);
        std::swap(current, next);
    }
    return current;
}

void Compositor::record_composite(VkCommandBuffer cmd, const FloorStep& step, GpuImage& floor,
                                  const std::vector<PixelRect>* rects, bool expanding,
                                  FloorFrameReport& report) {
    // The floor over the accumulation, only where the floor's stencil says 1 (or, after a
    // coverage-expanding effect, wherever the floor is not fully transparent). The stencil is
    // attached again: the barrier makes the tile pass's stencil writes visible to this load.
    const PixelRect area = expanding ? expansion_areas_[step.floor] : step.scissor;
    const StencilAttachment stencil{targets_.floor_stencil(), LoadOp::Keep, 0, false};
    begin_rendering(cmd, area, {&targets_.accumulation(), LoadOp::Keep}, &stencil);
    set_scissor(cmd, area);
    bind(cmd, expanding ? HostPass::CompositeByAlpha : HostPass::Composite, floor.view(),
         floor.view(), pipelines_->nearest_sampler());
    CompositePushConstants push;
    push.violation_slot = step.floor;
    pipelines_->push(cmd, push);
    uint64_t composited = area.area();
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
    final_accumulation_ = &targets_.accumulation();
    const size_t run = std::min<size_t>(global_effects_.size(), global_effects_run_);
    if (run == 0) return;
    FloorFrameReport report;
    report.floor = UINT32_MAX;
    report.path = "global";
    report.why = "global effects on the composite";
    report.scissor = {0, 0, int64_t(width_), int64_t(height_)};
    // Every pass of a global effect writes every pixel of "result".
    const EffectChain chain{&global_effects_,
                            run,
                            &targets_.accumulation(),
                            targets_.accumulation_pingpong(),
                            report.scissor,
                            report.scissor,
                            false,
                            nullptr};
    GpuImage* current = record_effect_chain(cmd, chain, time, report);
    final_accumulation_ = current;
    stats.passes += report.passes;
    stats.pixels_shaded += report.pixels_shaded;
    stats.global = report;
}

void Compositor::record_output(VkCommandBuffer cmd, FrameStats& stats) {
    GpuImage& accumulation = final_accumulation_ ? *final_accumulation_ : targets_.accumulation();
    GpuImage* floor_image = viewed_floor_ ? viewed_floor_ : targets_.floor_colour();
    accumulation.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const bool floor_view = view_reads_floor_target(options_.view) && floor_image;
    if (floor_view) floor_image->transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const PixelRect all{0, 0, int64_t(width_), int64_t(height_)};
    begin_rendering(cmd, all, {&targets_.output(), LoadOp::DontCare});  // every pixel written
    set_scissor(cmd, all);
    bind(cmd, HostPass::Output, accumulation.view(),
         floor_view ? floor_image->view() : accumulation.view(), pipelines_->nearest_sampler());
    OutputPushConstants push;
    std::copy(scene_.background.begin(), scene_.background.end(), push.background);
    push.view = uint32_t(options_.view);
    pipelines_->push(cmd, push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    if (timer_) timer_->mark(cmd, "output");
    ++stats.passes;
    stats.pixels_shaded += all.area();
}

void Compositor::record_frame(VkCommandBuffer cmd, const FramePlan& plan, FrameStats& stats,
                              double time) {
    viewed_floor_ = targets_.floor_colour();
    if (timer_) timer_->begin(cmd);
    clear_image(cmd, targets_.accumulation());
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
        clear_image(cmd, *targets_.floor_colour());
        viewed_floor_ = targets_.floor_colour();
    }
    record_global_effects(cmd, stats, time);
    record_output(cmd, stats);
}

}  // namespace acetate
