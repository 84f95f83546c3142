// Compositor: render() (plan the frame, record it through floor_recording.cpp, submit, count
// what it did), the read-backs and what the loaded scene holds. Loading is in
// compositor_load.cpp.
#include "render/compositor.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstring>

#include "core/elapsed.hpp"
#include "render/renderer.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {

Compositor::Compositor(Renderer& renderer) : renderer_(renderer), context_(renderer.context()) {}

Compositor::~Compositor() {
    if (context_.device()) vkDeviceWaitIdle(context_.device());
}

Result<FrameStats> Compositor::render(uint32_t active_floor, double time) {
    if (active_floor >= floor_count())
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{}: active floor {} does not exist (the scene has {} "
                        "floors, 0..{})",
                        scene_.file.string(), active_floor, floor_count(), floor_count() - 1));
    if (view_reads_floor_target(options_.view) && !targets_.has(SharedRole::FloorColour))
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("view \"{}\" needs a floor target; load the scene with it",
                                      to_string(options_.view)));
    const auto start = std::chrono::steady_clock::now();
    const ResourceCounters before = context_.counters();
    auto compiled = frame_for(active_floor);
    if (!compiled) return compiled.error();
    const FrameShape& shape = *compiled.value();
    last_plan_ = shape.plan;
    final_accumulation_ = shape.final_accumulation;
    viewed_floor_ = shape.viewed_floor;

    FrameStats stats;
    stats.active_floor = active_floor;
    GpuBuffer& violations = targets_.violations();
    std::memset(violations.mapped(), 0, violations.size());
    ACETATE_TRY(context_.submit_and_wait([&](VkCommandBuffer cmd) {
        if (timer_) timer_->begin(cmd);
        shape.frame.execute(cmd, time, stats);
    }));
    stats.milliseconds = milliseconds_since(start);
    if (timer_) {
        auto timings = timer_->read();
        if (!timings) return timings.error();
        stats.gpu_passes = std::move(timings.value());
    }

    const auto* counts = static_cast<const uint32_t*>(violations.mapped());
    for (FloorFrameReport& f : stats.floors) {
        f.violations = counts[f.floor];
        stats.violations += f.violations;
    }
    const ResourceCounters used = context_.counters() - before;
    stats.images_loaded = used.images_loaded;
    stats.targets_allocated = used.targets_allocated;
    stats.shaders_compiled = used.shaders_compiled;
    stats.pipelines_created = used.pipelines_created;
    stats.barriers = used.barriers_recorded;
    return stats;
}

Result<const Compositor::FrameShape*> Compositor::frame_for(uint32_t active_floor) {
    const FrameKey key{active_floor, options_.view, effects_enabled_, floor_effects_run_,
                       global_effects_run_};
    if (auto found = frames_.find(key); found != frames_.end()) return &found->second;
    PlanOptions plan_options = options_.plan;
    if (view_reads_floor_target(options_.view)) plan_options.force_target_floor = active_floor;
    if (options_.inject) plan_options.draw_direct = false;  // the hook acts like an effect
    const FramePlan plan = plan_frame(width_, height_, geometry_, active_floor, plan_options);
    auto shape = compile_frame(plan, active_floor);
    if (!shape) return shape.error();
    ++frames_compiled_;
    return &frames_.emplace(key, std::move(shape.value())).first->second;
}

Result<ImageRGBA> Compositor::read_output() {
    return read_back_image(context_, targets_.output());
}
Result<ImageRGBA> Compositor::read_accumulation() {
    return read_back_image(context_,
                           final_accumulation_ ? *final_accumulation_ : targets_.accumulation());
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
    return targets_.infos();
}

std::vector<TargetInfo> Compositor::images_held() const {
    std::vector<TargetInfo> out = targets_held();
    std::vector<const GpuImage*> images = resources_->images();
    for (const auto& floor : view_masks_)
        for (const auto& [kind, image] : floor) images.push_back(&image);
    if (view_blank_mask_) images.push_back(&*view_blank_mask_);
    for (const GpuImage* image : images)
        out.push_back({image->name(), format_name(image->format()), image->width(), image->height(),
                       image->bytes()});
    return out;
}

}  // namespace acetate
