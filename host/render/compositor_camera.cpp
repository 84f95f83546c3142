// The camera (ABI 1.2): which region of the scene a frame shows, and at what scale. A move at
// the same scale and output size is a few numbers: the planner's areas again in render pixels,
// the uniforms each frame writes anyway, and the floors' masks resampled into their
// render-pixel copies. Another scale runs every effect's build() again, told the new scale
// (an effect whose passes come out the same keeps its instance); another output size also
// allocates the frame's targets and every effect's own targets again. Everything new is made
// before anything is swapped in, so a refusal leaves the scene as it was.
#include <fmt/format.h>

#include <cmath>

#include "render/compositor.hpp"  // the class whose camera half this is
#include "render/renderer.hpp"
#include "vulkan/render_commands.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {
namespace {

// The scene's entry of an instance: its field ("floors[1].effects[0]") names it in errors.
const EffectRef& entry_of(const SceneDesc& scene, const EffectInstance& instance) {
    return instance.floor < 0 ? scene.global_effects[instance.scene_index]
                              : scene.floors[size_t(instance.floor)].effects[instance.scene_index];
}

// An error about that entry, with the fields a program acts on.
Error about(ErrorCode code, std::string message, const SceneDesc& scene,
            const EffectInstance& instance) {
    Error error = make_error(code, std::move(message));
    error.file = scene.file.string();
    error.field = entry_of(scene, instance).where;
    error.plugin = instance.plugin->descriptor.id;
    if (instance.floor >= 0) error.floor = uint32_t(instance.floor);
    return error;
}

}  // namespace

Result<void> Compositor::set_view_transform(const ViewTransform& view) {
    const std::string file = scene_.file.string();
    if (view == view_) return {};
    const uint32_t max_dim = context_.properties().limits.maxImageDimension2D;
    if (view.width == 0 || view.height == 0 || view.width > max_dim || view.height > max_dim)
        return make_error(
            ErrorCode::DeviceLimit,
            fmt::format("{}: camera: an output of {}x{} pixels; device \"{}\" "
                        "allows 1 to {} per side",
                        file, view.width, view.height, context_.device_name(), max_dim));
    if (!std::isfinite(view.x) || !std::isfinite(view.y) || !std::isfinite(view.scale) ||
        view.scale <= 0)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: camera: origin ({}, {}) and scale {} must be finite, "
                                      "the scale above 0",
                                      file, view.x, view.y, view.scale));
    // A plugin built before 1.2 takes gl_FragCoord for scene pixels: under any other camera it
    // would light, ripple and burn the wrong places.
    if (!view.is_whole(scene_.width, scene_.height)) {
        std::vector<const EffectInstance*> all;
        for (const auto& floor : floor_effects_)
            for (const auto& e : floor) all.push_back(e.get());
        for (const auto& e : global_effects_) all.push_back(e.get());
        for (const EffectInstance* e : all)
            if (e->plugin->descriptor.abi_minor < 2)
                return about(
                    ErrorCode::InvalidInput,
                    fmt::format("{}: {}: plugin \"{}\" was built against ABI 1.{}, which has no "
                                "camera: it renders only the whole canvas at scale 1 (rebuild "
                                "it against ABI 1.2)",
                                file, entry_of(scene_, *e).where, e->plugin->descriptor.id,
                                e->plugin->descriptor.abi_minor),
                    scene_, *e);
    }

    const ViewTransform before = view_;
    const bool resized = view.width != before.width || view.height != before.height;
    const bool rescaled = resized || view.scale != before.scale;
    std::optional<FrameTargets> new_targets;
    if (resized) {
        new_targets.emplace();
        ACETATE_TRY(new_targets->allocate(context_, view.width, view.height, options_.format,
                                          target_needs(), file + ": camera"));
    }
    view_ = view;
    width_ = view.width;
    height_ = view.height;
    if (rescaled)
        if (auto rebuilt = rebuild_for_view(new_targets ? &*new_targets : nullptr); !rebuilt) {
            view_ = before;
            width_ = before.width;
            height_ = before.height;
            return rebuilt.error();
        }
    plan_geometry(scene_);
    for (auto& floor : floor_effects_)
        for (auto& e : floor) count_instanced_pixels(*e, view_);
    for (auto& e : global_effects_) count_instanced_pixels(*e, view_);
    ACETATE_TRY(view_masks());
    // lavapipe compiles a shader variant per sampler and texture size at the first draw: the
    // warm-up draws each once (tiles switch between nearest and linear with the alignment).
    if (rescaled || before.pixel_aligned() != view_.pixel_aligned()) ACETATE_TRY(warm_pipelines());
    if (timer_ && rescaled) create_timer();  // one mark per pass: the count may have changed
    return {};
}

Result<void> Compositor::rebuild_for_view(FrameTargets* new_targets) {
    InstanceSetup setup;
    setup.format = options_.format;
    setup.checked_builtins = options_.checked_builtins;
    setup.view = view_;
    setup.targets = new_targets ? &new_targets->effect_targets() : &targets_.effect_targets();
    const std::string file = scene_.file.string();
    // One instance for the new view, or null when it may stay (same passes, same targets).
    auto rebuild = [&](const EffectInstance& instance) -> Result<std::unique_ptr<EffectInstance>> {
        const EffectRef& ref = entry_of(scene_, instance);
        setup.masks = nullptr;
        if (instance.floor >= 0 && !instance.plugin->descriptor.masks.empty()) {
            // build() may read its floor's masks (read_mask): the composites the load made.
            if (!live_masks_) {
                auto masks = composite_scene_masks(scene_, options_.mask_kinds);
                if (!masks) return masks.error();
                live_masks_ = std::move(masks.value());
            }
            setup.masks = &live_masks_->floors[size_t(instance.floor)];
        }
        auto prepared = prepare_effect_instance(renderer_, scene_, ref, instance.floor, setup);
        if (!prepared) return prepared.error();
        if (!new_targets && prepared->instance->graph_digest == instance.graph_digest)
            return std::unique_ptr<EffectInstance>();
        // The floor's targets and host passes were chosen for this coverage and for an effect
        // that runs.
        if (prepared->instance->expanding != instance.expanding || prepared->graph.passes.empty())
            return about(
                ErrorCode::InvalidInput,
                fmt::format("{}: {}: at scale {} build() declared {}", file, ref.where, view_.scale,
                            prepared->graph.passes.empty()
                                ? "no pass, where it declared passes at load"
                                : "another coverage than at load"),
                scene_, instance);
        auto created = create_effect_instance(renderer_, scene_, ref, instance.floor, setup,
                                              std::move(prepared.value()));
        if (!created) return created.error();
        created.value()->scene_index = instance.scene_index;
        return created;
    };
    // Everything first; nothing is swapped in unless every instance succeeded.
    std::vector<std::vector<std::unique_ptr<EffectInstance>>> floors(floor_effects_.size());
    for (size_t f = 0; f < floor_effects_.size(); ++f)
        for (const auto& e : floor_effects_[f]) {
            auto next = rebuild(*e);
            if (!next) return next.error();
            floors[f].push_back(std::move(next.value()));
        }
    std::vector<std::unique_ptr<EffectInstance>> globals;
    for (const auto& e : global_effects_) {
        auto next = rebuild(*e);
        if (!next) return next.error();
        globals.push_back(std::move(next.value()));
    }
    // The frames before used the old instances and targets: they are finished (every frame is
    // waited for), so those can go now.
    invalidate_frames();  // they named the old instances and targets
    if (new_targets) targets_ = std::move(*new_targets);
    for (size_t f = 0; f < floors.size(); ++f)
        for (size_t i = 0; i < floors[f].size(); ++i)
            if (floors[f][i]) floor_effects_[f][i] = std::move(floors[f][i]);
    for (size_t i = 0; i < globals.size(); ++i)
        if (globals[i]) global_effects_[i] = std::move(globals[i]);
    return {};
}

Result<void> Compositor::view_masks() {
    const bool camera = !view_.is_whole(scene_.width, scene_.height);
    auto bind_all = [&] {
        for (uint32_t f = 0; f < floor_effects_.size(); ++f)
            for (auto& e : floor_effects_[f]) bind_masks(*e, f);
    };
    if (!camera || options_.mask_kinds.empty()) {
        view_masks_.clear();
        view_blank_mask_.reset();
        bind_all();
        return {};
    }
    constexpr VkImageUsageFlags kUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                         VK_IMAGE_USAGE_SAMPLED_BIT |
                                         VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (!view_blank_mask_ || view_blank_mask_->width() != width_ ||
        view_blank_mask_->height() != height_) {
        std::vector<std::map<std::string, GpuImage>> masks(floor_count());
        for (uint32_t f = 0; f < floor_count(); ++f)
            for (const auto& [kind, scene_mask] : resources_->floors()[f].masks) {
                auto image =
                    GpuImage::create(context_, fmt::format("floor{}.mask.{}.view", f, kind), width_,
                                     height_, options_.format, kUsage, true);
                if (!image) return image.error();
                masks[f].emplace(kind, std::move(image.value()));
            }
        auto blank = GpuImage::create(context_, "mask.blank.view", width_, height_, options_.format,
                                      kUsage, true);
        if (!blank) return blank.error();
        view_masks_ = std::move(masks);
        view_blank_mask_ = std::move(blank.value());
    }
    ACETATE_TRY(pipelines_->ensure(HostPass::MaskView, options_.format));
    const PixelRect all{0, 0, int64_t(width_), int64_t(height_)};
    MaskViewPushConstants push;
    push.view[0] = float(view_.x), push.view[1] = float(view_.y);
    push.view[2] = float(view_.scale), push.view[3] = float(1 / view_.scale);
    push.canvas[0] = float(scene_.width), push.canvas[1] = float(scene_.height);
    push.canvas[2] = 1.0f / float(scene_.width), push.canvas[3] = 1.0f / float(scene_.height);
    // Whole pixels at scale 1 read each texel as it is: lavapipe's linear filter weighs even a
    // texel centre with fixed-point weights that are not exactly 1 and 0.
    const VkSampler sampler =
        view_.pixel_aligned() ? pipelines_->nearest_sampler() : pipelines_->linear_sampler();
    // A compiled frame of its own (render/compiled_frame.hpp): the barriers are planned.
    FrameBuilder frame;
    GpuImage* blank = &*view_blank_mask_;
    frame.add(
        "clear " + blank->name(), {{blank, ImageAccess::TransferWrite}},
        ReportIndex(ReportSlot::Frame), [blank](PassRecording& r) { clear_image(r.cmd, *blank); },
        true);
    std::vector<std::pair<GpuImage*, ImageAccess>> sampled{{blank, ImageAccess::Sampled}};
    for (uint32_t f = 0; f < floor_count(); ++f)
        for (const auto& [kind, scene_mask] : resources_->floors()[f].masks) {
            GpuImage* out = &view_masks_[f].at(kind);
            const GpuImage* in = &scene_mask;
            sampled.emplace_back(out, ImageAccess::Sampled);
            frame.add(
                "resample " + out->name(), {{out, ImageAccess::ColourWrite}},
                ReportIndex(ReportSlot::Frame),
                [this, out, in, all, push, sampler](PassRecording& r) {
                    begin_rendering(r.cmd, all, {out, LoadOp::DontCare});  // every pixel written
                    set_scissor(r.cmd, all);
                    bind(r.cmd, HostPass::MaskView, in->view(), in->view(), sampler);
                    pipelines_->push(r.cmd, push);
                    vkCmdDraw(r.cmd, 3, 1, 0, 0);
                    vkCmdEndRendering(r.cmd);
                },
                true);
        }
    // Frames sample the masks without naming them (they are written only here and at load), so
    // this one leaves them in the layout of a sampled image: a pass of barriers alone.
    frame.add(
        "masks ready to sample", std::move(sampled), ReportIndex(ReportSlot::Frame),
        [](PassRecording&) {}, true);
    const CompiledFrame compiled = frame.compile({}, {}, std::nullopt);
    FrameStats ignored;
    ACETATE_TRY(
        context_.submit_and_wait([&](VkCommandBuffer cmd) { compiled.execute(cmd, 0, ignored); }));
    bind_all();
    return {};
}

}  // namespace acetate
