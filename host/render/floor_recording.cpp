// A frame as passes (compiled_frame.hpp): each floor up to the active one drawn directly into
// the accumulation or through its own target (tiles with the stencil, effects, composite), then
// the global effects and the output pass, each pass naming the images it reads and writes.
// Compiled once per frame shape (Compositor::frame_for, compositor.cpp); a pass records its
// commands when the compiled frame runs, reading the time and the camera of that frame.
#include <fmt/format.h>

#include <algorithm>

#include "render/compositor.hpp"  // the class whose frames this builds
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

void Compositor::add_floors_direct(FrameBuilder& frame, const std::vector<FloorStep>& steps,
                                   size_t first, size_t end,
                                   std::vector<FloorFrameReport>& reports) {
    // Consecutive floors drawn directly share one rendering pass over the union of their
    // scissors: blending happens in draw order within a pass, so this is the same "over" as one
    // pass per floor, without the barrier and the pass set-up between floors. Each floor's
    // draws keep their own scissor.
    PixelRect area;
    for (size_t i = first; i < end; ++i)
        if (steps[i].path == FloorPath::Direct) area = bounding_union(area, steps[i].scissor);
    const size_t first_report = reports.size();
    for (size_t i = first; i < end; ++i) reports.push_back(frame_report(steps[i]));
    std::vector<FloorStep> run(steps.begin() + ptrdiff_t(first), steps.begin() + ptrdiff_t(end));
    const std::string name = first + 1 == end
                                 ? fmt::format("floor {} tiles", steps[first].floor)
                                 : fmt::format("floors {}-{} tiles (one pass)", steps[first].floor,
                                               steps[end - 1].floor);
    frame.add(name, {{&targets_.accumulation(), ImageAccess::ColourWrite}},
              ReportIndex(first_report), [this, area, run, first_report, name](PassRecording& r) {
                  begin_rendering(r.cmd, area, {&targets_.accumulation(), LoadOp::Keep});
                  // Over is associative, so drawing each tile over the accumulation equals
                  // compositing the floor's own "tiles over transparent" image over it
                  // (docs/OVERVIEW.md).
                  for (size_t k = 0; k < run.size(); ++k)
                      if (run[k].path == FloorPath::Direct)
                          draw_tiles(r.cmd, HostPass::TileToAccum, run[k].floor, run[k].scissor,
                                     (*r.floors)[first_report + k]);
                  vkCmdEndRendering(r.cmd);
                  if (timer_) timer_->mark(r.cmd, name);
              });
}

GpuImage* Compositor::add_floor_through_target(FrameBuilder& frame, const FloorStep& step,
                                               bool clear_all, ReportIndex report,
                                               const RoleImages& roles) {
    GpuImage& colour = *roles[SharedRole::FloorColour];
    GpuImage& stencil = *targets_.floor_stencil();
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
    frame.add(fmt::format("floor {} tiles", step.floor),
              {{&colour, ImageAccess::ColourWrite}, {&stencil, ImageAccess::StencilWrite}}, report,
              [this, step, area, &colour](PassRecording& r) {
                  const StencilAttachment stencil{targets_.floor_stencil(), LoadOp::Clear, 0, true};
                  begin_rendering(r.cmd, area, {&colour, LoadOp::Clear}, &stencil);
                  draw_tiles(r.cmd, HostPass::TileToTarget, step.floor, step.scissor, *r.report);
                  if (options_.inject) record_injection(r.cmd, step.scissor, *r.report);
                  vkCmdEndRendering(r.cmd);
                  if (timer_) timer_->mark(r.cmd, fmt::format("floor {} tiles", step.floor));
              });

    GpuImage* floor = &colour;
    const auto& effects = floor_effects_[step.floor];
    if (!effects.empty() && effects_enabled_ && floor_effects_run_ > 0) {
        // An expanding effect (or any effect of a floor that has one) writes where the floor's
        // coverage may grow to; the others within the floor's scissor.
        const EffectChain chain{&effects,     std::min<size_t>(effects.size(), floor_effects_run_),
                                &colour,      roles[SharedRole::FloorPingpong],
                                step.scissor, expansion_areas_[step.floor],
                                expanding,    rects,
                                report,       fmt::format("floor {}", step.floor)};
        floor = add_effect_chain(frame, chain);
    }
    // The floor over the accumulation, only where the floor's stencil says 1 (or, after a
    // coverage-expanding effect, wherever the floor is not fully transparent).
    const PixelRect composite_area = expanding ? expansion_areas_[step.floor] : step.scissor;
    frame.add(fmt::format("floor {} composite", step.floor),
              {{floor, ImageAccess::Sampled},
               {&stencil, ImageAccess::StencilTest},
               {&targets_.accumulation(), ImageAccess::ColourWrite}},
              report, [this, step, floor, rects, expanding, composite_area](PassRecording& r) {
                  record_composite(r.cmd, step, *floor, composite_area, rects, expanding,
                                   *r.report);
              });
    return floor;
}

void Compositor::record_injection(VkCommandBuffer cmd, const PixelRect& scissor,
                                  FloorFrameReport& report) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                      pipelines_->pipeline(inject_pass(), options_.format));
    InjectPushConstants push;
    std::copy(options_.inject->colour.begin(), options_.inject->colour.end(), push.colour);
    pipelines_->push(cmd, push);
    set_scissor(cmd, scissor);  // like any pass: inside the render area
    vkCmdDraw(cmd, 3, 1, 0, 0);
    ++report.passes;
    report.pixels_shaded += scissor.area();
}

GpuImage* Compositor::add_effect_chain(FrameBuilder& frame, const EffectChain& chain) {
    GpuImage* current = chain.current;
    GpuImage* next = chain.next;
    frame.add(chain.name + " clear " + next->name(), {{next, ImageAccess::TransferWrite}},
              chain.report, [next](PassRecording& r) { clear_image(r.cmd, *next); });
    for (size_t i = 0; i < chain.run; ++i) {
        EffectInstance* effect = (*chain.effects)[i].get();
        const PixelRect scissor =
            effect->expanding || chain.expanding ? chain.expanded : chain.scissor;
        // What "result" holds before this effect writes it: the poison where its passes
        // shade, the zeros (or tiles) of today elsewhere.
        if (options_.poison)
            frame.add(effect->label + " poison", {{next, ImageAccess::ColourWrite}}, chain.report,
                      [this, next, scissor, rects = chain.rects](PassRecording& r) {
                          if (rects)
                              for (const PixelRect& rect : *rects)
                                  fill_area(r.cmd, *next, rect, *options_.poison);
                          else
                              fill_area(r.cmd, *next, scissor, *options_.poison);
                      });
        add_effect_passes(frame, {effect, current, next, scissor, chain.rects, chain.report});
        std::swap(current, next);
    }
    return current;
}

void Compositor::add_effect_passes(FrameBuilder& frame, const EffectPasses& at) {
    // Images a frame writes (the pair, the effects' own targets): an effect's input among them
    // is a use the graph orders; the others (masks, textures, the blank texture) are written at
    // load only.
    const std::vector<GpuImage*> written = targets_.images();
    auto is_written = [&](const GpuImage* image) {
        return image == at.previous || image == at.result ||
               std::find(written.begin(), written.end(), image) != written.end();
    };
    for (size_t p = 0; p < at.effect->passes.size(); ++p) {
        const EffectPassRuntime& pass = at.effect->passes[p];
        EffectIo io;
        io.previous = at.previous;
        io.result = at.result;
        std::vector<std::pair<GpuImage*, ImageAccess>> uses;
        for (size_t b = 0; b < pass.inputs.size(); ++b) {
            const GpuImage* input = effect_pass_input(pass, b, io);
            if (is_written(input))
                uses.emplace_back(const_cast<GpuImage*>(input), ImageAccess::Sampled);
        }
        uses.emplace_back(effect_pass_output(pass, io), ImageAccess::ColourWrite);
        frame.add(
            pass.label, std::move(uses), at.report,
            [this, at, p](PassRecording& r) {
                EffectIo io = effect_io(r.time);
                io.previous = at.previous;
                io.result = at.result;
                io.result_scissor = at.scissor;
                io.result_rects = at.rects;
                if (at.warm_up) {
                    io.timer = nullptr;
                    io.warm_up = true;
                }
                record_effect_pass(r.cmd, renderer_, *at.effect, p, io, *r.report);
            },
            at.warm_up);
    }
}

void Compositor::record_composite(VkCommandBuffer cmd, const FloorStep& step, GpuImage& floor,
                                  const PixelRect& area, const std::vector<PixelRect>* rects,
                                  bool expanding, FloorFrameReport& report) {
    // The stencil is attached again, only tested: the tile pass's writes were made visible to
    // this pass by the barrier the compiled frame planned between them.
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

GpuImage* Compositor::add_global_effects(FrameBuilder& frame,
                                         std::optional<FloorFrameReport>& global,
                                         const RoleImages& roles) {
    const size_t run = std::min<size_t>(global_effects_.size(), global_effects_run_);
    if (run == 0) return &targets_.accumulation();
    global.emplace();
    global->floor = UINT32_MAX;
    global->path = "global";
    global->why = "global effects on the composite";
    global->scissor = {0, 0, int64_t(width_), int64_t(height_)};
    // Every pass of a global effect writes every pixel of "result".
    const EffectChain chain{&global_effects_,
                            run,
                            &targets_.accumulation(),
                            roles[SharedRole::CompositePingpong],
                            global->scissor,
                            global->scissor,
                            false,
                            nullptr,
                            ReportIndex(ReportSlot::Global),
                            "global"};
    return add_effect_chain(frame, chain);
}

void Compositor::add_output(FrameBuilder& frame, GpuImage& accumulation, GpuImage* floor_image) {
    // The output reads the composite, and in a floor view the active floor's own target too.
    std::vector<std::pair<GpuImage*, ImageAccess>> uses{{&accumulation, ImageAccess::Sampled}};
    if (floor_image && floor_image != &accumulation)
        uses.emplace_back(floor_image, ImageAccess::Sampled);
    uses.emplace_back(&targets_.output(), ImageAccess::ColourWrite);
    frame.add(
        "output", std::move(uses), ReportIndex(ReportSlot::Frame),
        [this, &accumulation, floor_image](PassRecording& r) {
            const PixelRect all{0, 0, int64_t(width_), int64_t(height_)};
            // Every pixel is written: nothing is loaded.
            begin_rendering(r.cmd, all, {&targets_.output(), LoadOp::DontCare});
            set_scissor(r.cmd, all);
            bind(r.cmd, HostPass::Output, accumulation.view(),
                 floor_image ? floor_image->view() : accumulation.view(),
                 pipelines_->nearest_sampler());
            OutputPushConstants push;
            std::copy(scene_.background.begin(), scene_.background.end(), push.background);
            push.view = uint32_t(options_.view);
            pipelines_->push(r.cmd, push);
            vkCmdDraw(r.cmd, 3, 1, 0, 0);
            vkCmdEndRendering(r.cmd);
            if (timer_) timer_->mark(r.cmd, "output");
            ++r.report->passes;
            r.report->pixels_shaded += all.area();
        },
        true);
}

Compositor::FrameBuild Compositor::build_frame(const FramePlan& plan, uint32_t active_floor,
                                               const RoleImages& roles) {
    FrameBuild out;
    FrameBuilder& frame = out.builder;
    frame.add("clear accumulation", {{&targets_.accumulation(), ImageAccess::TransferWrite}},
              ReportIndex(ReportSlot::Frame), [this](PassRecording& r) {
                  clear_image(r.cmd, targets_.accumulation());
                  if (timer_) timer_->mark(r.cmd, "clear");
              });
    const bool floor_view = view_reads_floor_target(options_.view);
    GpuImage* viewed = roles[SharedRole::FloorColour];
    const std::vector<FloorStep>& steps = plan.steps;
    for (size_t i = 0; i < steps.size();) {
        if (steps[i].path == FloorPath::Direct) {
            // The run of floors up to the next one with a target (skipped floors record
            // nothing, so they do not break it).
            size_t end = i + 1;
            while (options_.plan.merge_direct_floors && end < steps.size() &&
                   steps[end].path != FloorPath::ThroughTarget)
                ++end;
            add_floors_direct(frame, steps, i, end, out.reports);
            i = end;
            continue;
        }
        const FloorStep& step = steps[i++];
        out.reports.push_back(frame_report(step));
        if (step.path == FloorPath::ThroughTarget) {
            const bool is_viewed = floor_view && step.floor == active_floor;
            viewed = add_floor_through_target(frame, step, is_viewed,
                                              ReportIndex(out.reports.size() - 1), roles);
        }
    }
    if (floor_view && steps.back().path != FloorPath::ThroughTarget) {
        // The active floor drew nothing (it covers no pixel), so its target must read as empty,
        // not as whatever a lower floor left in the shared target.
        viewed = roles[SharedRole::FloorColour];
        frame.add("clear the active floor's target", {{viewed, ImageAccess::TransferWrite}},
                  ReportIndex(ReportSlot::Frame),
                  [viewed](PassRecording& r) { clear_image(r.cmd, *viewed); });
    }
    GpuImage* accumulation = add_global_effects(frame, out.global, roles);
    add_output(frame, *accumulation, floor_view ? viewed : nullptr);
    out.final_accumulation = accumulation;
    out.viewed_floor = viewed;
    // Read after the frame: the output, the composite (read_accumulation), in a floor view the
    // active floor's target (read_active_floor), and the effects' own targets, which keep what
    // a frame wrote for the next (a plugin that reads one before writing it is caught by the
    // harness's isolation checks, which must see it).
    out.read_after = {&targets_.output(), accumulation, floor_view ? viewed : nullptr};
    for (const GpuImage* image : targets_.effect_targets().images())
        out.read_after.push_back(image);
    return out;
}

Result<Compositor::FrameShape> Compositor::compile_frame(const FramePlan& plan,
                                                         uint32_t active_floor) {
    // Built first over one stand-in per role, to learn which passes run and when each role is
    // used; then built again over the images share_images gives the roles, without the passes
    // that do not run (the same passes in the same order: a build depends only on the plan,
    // the options and the roles' images).
    const RoleImages stand_ins = targets_.stand_ins();
    FrameBuild first = build_frame(plan, active_floor, stand_ins);
    const FrameGraphPlan spans = first.builder.plan(first.read_after);
    const std::vector<GpuImage*>& images = first.builder.images();
    auto index_of = [&](const GpuImage* image) {
        return uint32_t(std::find(images.begin(), images.end(), image) - images.begin());
    };
    std::vector<bool> shareable(images.size(), false);
    for (GpuImage* stand_in : stand_ins.image)
        if (stand_in && index_of(stand_in) < images.size()) shareable[index_of(stand_in)] = true;
    SharedSlots slots = share_images(spans, shareable, first.builder.read_flags(first.read_after));
    if (!options_.plan.share_targets) {
        // One image per role, in the roles' order (to compare: render/frame_targets.hpp).
        uint32_t next = 0;
        for (GpuImage* stand_in : stand_ins.image) {
            if (!stand_in) continue;
            if (index_of(stand_in) < images.size()) slots.slot[index_of(stand_in)] = next;
            slots.count = ++next;
        }
    }
    std::vector<GpuImage>& shared = targets_.shared();
    // Not expected (frame_targets.hpp says why two suffice); refused rather than drawn wrong.
    if (slots.count > shared.size())
        return make_error(
            ErrorCode::OutOfMemory,
            fmt::format("{}: the frame for floor {} needs {} transient targets at "
                        "once; {} were allocated at load",
                        scene_.file.string(), active_floor, slots.count, shared.size()));
    RoleImages roles;
    for (size_t r = 0; r < kSharedRoles; ++r) {
        GpuImage* stand_in = stand_ins.image[r];
        if (!stand_in) continue;
        const uint32_t index = index_of(stand_in);
        const uint32_t slot = index < images.size() ? slots.slot[index] : SharedSlots::kNone;
        // A role no running pass uses is named only by passes that are dropped below.
        roles.image[r] = &shared[slot == SharedSlots::kNone ? 0 : slot];
    }
    FrameBuild second = build_frame(plan, active_floor, roles);
    second.builder.drop(spans.culled);
    FrameShape shape;
    shape.plan = plan;
    shape.final_accumulation = second.final_accumulation;
    shape.viewed_floor = second.viewed_floor;
    shape.frame = second.builder.compile(second.read_after, std::move(second.reports),
                                         std::move(second.global));
    return shape;
}

}  // namespace acetate
