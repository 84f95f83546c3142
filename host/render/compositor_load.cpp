// Compositor::load and what it does once per scene: plugins built into effect instances (and
// those that declared nothing dropped), masks, targets, pipelines compiled and warmed. Frames
// are recorded in compositor.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <set>

#include "render/compositor.hpp"  // the class whose loading half this is
#include "render/compositor_internal.hpp"
#include "render/renderer.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {
using namespace compositor_detail;

Result<SceneMasks> Compositor::create_effects(const SceneDesc& scene) {
    // Masks are decoded and composited only for kinds some floor effect declares, once, before
    // any build() (which may read them) and for the GPU alike. A plugin that fails to load
    // here is reported, with its field, by create_effect_instance below.
    for (const FloorDesc& floor : scene.floors)
        for (const EffectRef& ref : floor.effects)
            if (auto plugin = renderer_.plugins().load(ref.plugin))
                for (const std::string& kind : plugin.value()->descriptor.masks)
                    options_.mask_kinds.insert(kind);
    auto masks = composite_scene_masks(scene, options_.mask_kinds);
    if (!masks) return masks.error();

    InstanceSetup setup;
    setup.format = options_.format;
    setup.targets = &effect_targets_;
    setup.checked_builtins = options_.checked_builtins;
    floor_effects_.resize(scene.floors.size());
    for (size_t f = 0; f < scene.floors.size(); ++f) {
        setup.masks = &masks->floors[f];
        for (const EffectRef& ref : scene.floors[f].effects) {
            auto instance = create_effect_instance(renderer_, scene, ref, int64_t(f), setup);
            if (!instance) return instance.error();
            // An instance that declared nothing (water on a floor without water) is dropped:
            // the floor then renders exactly as if the scene had not listed the effect.
            if (instance.value()->passes.empty()) continue;
            floor_effects_[f].push_back(std::move(instance.value()));
        }
    }
    setup.masks = nullptr;
    for (const EffectRef& ref : scene.global_effects) {
        auto instance = create_effect_instance(renderer_, scene, ref, -1, setup);
        if (!instance) return instance.error();
        if (instance.value()->passes.empty()) continue;
        global_effects_.push_back(std::move(instance.value()));
    }
    return masks;
}

PixelRect Compositor::expansion_area(const SceneDesc& scene, size_t floor) const {
    // Effects run one after another, so their reaches add up. One expanding effect without a
    // declared reach may change any pixel.
    const PixelRect canvas{0, 0, int64_t(scene.width), int64_t(scene.height)};
    if (options_.ignore_declared_reach) return canvas;
    int64_t reach = 0;
    for (const auto& e : floor_effects_[floor]) {
        if (!e->expanding) continue;
        if (!e->reach) return canvas;
        reach += *e->reach;
    }
    const PixelRect bounds = floor_coverage_bounds(scene, floor);
    if (bounds.empty()) return bounds;
    return intersect(canvas, PixelRect{bounds.x0 - reach, bounds.y0 - reach, bounds.x1 + reach,
                                       bounds.y1 + reach});
}

bool Compositor::declares_reach() const {
    for (const auto& floor : floor_effects_)
        for (const auto& e : floor)
            if (e->expanding && e->reach) return true;
    return false;
}

Result<std::unique_ptr<Compositor>> Compositor::load(Renderer& renderer, const SceneDesc& scene,
                                                     const CompositorOptions& options) {
    VulkanContext& context = renderer.context();
    const auto start = std::chrono::steady_clock::now();
    const ResourceCounters before = context.counters();
    if (options.format != VK_FORMAT_R16G16B16A16_SFLOAT &&
        options.format != VK_FORMAT_R32G32B32A32_SFLOAT)
        return make_error(ErrorCode::InvalidInput, "--format: expected rgba16f or rgba32f");
    const uint32_t max_dim = context.properties().limits.maxImageDimension2D;
    if (scene.width > max_dim || scene.height > max_dim)
        return make_error(ErrorCode::DeviceLimit,
                          fmt::format("{}: canvas: {}x{} exceeds the largest image device \"{}\" "
                                      "allows ({} per side)",
                                      scene.file.string(), scene.width, scene.height,
                                      context.device_name(), max_dim));
    if (scene.floors.empty())
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{}: floors: at least one floor is needed", scene.file.string()));

    std::unique_ptr<Compositor> out(new Compositor(renderer));
    out->options_ = options;
    out->scene_ = scene;
    out->width_ = scene.width;
    out->height_ = scene.height;
    out->pipelines_ = &renderer.host_pipelines();
    auto masks = out->create_effects(scene);
    if (!masks) return masks.error();

    // A floor whose effects all declared nothing is drawn as if it listed none, and only the
    // masks a remaining instance reads go to the GPU: a dropped instance costs nothing there.
    SceneDesc planned = scene;
    std::set<std::string> kinds_read;
    for (size_t f = 0; f < planned.floors.size(); ++f) {
        if (out->floor_effects_[f].empty()) planned.floors[f].effects.clear();
        std::set<std::string> floor_kinds;
        for (const auto& e : out->floor_effects_[f])
            floor_kinds.insert(e->plugin->descriptor.masks.begin(),
                               e->plugin->descriptor.masks.end());
        std::erase_if(masks->floors[f], [&](const auto& m) { return !floor_kinds.count(m.first); });
        kinds_read.insert(floor_kinds.begin(), floor_kinds.end());
    }
    for (const auto& e : out->global_effects_)
        kinds_read.insert(e->plugin->descriptor.masks.begin(), e->plugin->descriptor.masks.end());
    out->options_.mask_kinds = kinds_read;
    auto resources = SceneResources::load(context, planned, options.format,
                                          out->options_.mask_kinds, masks.value());
    if (!resources) return resources.error();
    out->resources_ = std::move(resources.value());
    // Each mask input now names the image a frame binds: the floor's composite of that kind, or
    // the scene-size transparent mask where the floor has none (a global effect reads no floor's
    // masks: the renderer's blank texture).
    const GpuImage& blank_texture = renderer.effect_pipelines().blank_texture();
    const GpuImage& blank_mask =
        out->resources_->blank_mask() ? *out->resources_->blank_mask() : blank_texture;
    for (size_t f = 0; f < out->floor_effects_.size(); ++f)
        for (auto& effect : out->floor_effects_[f])
            bind_pass_masks(*effect, &out->resources_->floors()[f].masks, blank_mask);
    for (auto& effect : out->global_effects_) bind_pass_masks(*effect, nullptr, blank_texture);
    ACETATE_TRY(out->create_targets(scene));

    // Only the stages this scene uses are compiled (once per process: the pool keeps them).
    std::vector<HostPass> stages{HostPass::Output};
    if (options.plan.draw_direct) stages.push_back(HostPass::TileToAccum);
    if (out->floor_color_) {
        stages.push_back(HostPass::TileToTarget);
        stages.push_back(HostPass::Composite);
        for (const auto& floor : out->floor_effects_)
            if (std::any_of(floor.begin(), floor.end(), [](const auto& e) { return e->expanding; }))
                stages.push_back(HostPass::CompositeByAlpha);
        if (options.inject) stages.push_back(out->inject_stage());
    }
    for (HostPass stage : stages)
        ACETATE_TRY(out->pipelines_->ensure(
            view_variant(stage, options.view == OutputView::Isolation), options.format));
    // The planner's view of each floor, fixed at load. A floor with a coverage-expanding effect
    // may draw past its tiles (a glow): for planning it covers its tiles grown by the effects'
    // declared reach, or the whole canvas when one declared none.
    out->geometry_ = out->resources_->geometry();
    for (size_t f = 0; f < out->floor_effects_.size(); ++f) {
        const auto& effects = out->floor_effects_[f];
        const bool expanding =
            std::any_of(effects.begin(), effects.end(), [](const auto& e) { return e->expanding; });
        out->expansion_areas_.push_back(expanding ? out->expansion_area(scene, f) : PixelRect{});
        if (expanding) out->geometry_[f].coverage = out->expansion_areas_.back();
        // A floor whose tiles lie far apart (houses, trees) would shade their whole bounding
        // box in every effect pass; its exact union as a few rects, one draw each, does not.
        // Past a handful of rects the draws cost more than the pixels they save.
        constexpr size_t kMaxShadingRects = 16;
        std::vector<PixelRect> rects;
        if (!effects.empty() && !expanding) {
            std::vector<PixelRect> tiles;
            for (const LoadedTile& tile : out->resources_->floors()[f].tiles)
                tiles.push_back(intersect(
                    tile.pixels, PixelRect{0, 0, int64_t(scene.width), int64_t(scene.height)}));
            rects = disjoint_union(tiles);
            if (rects.size() > kMaxShadingRects) rects.clear();
        }
        out->shading_rects_.push_back(std::move(rects));
    }
    ACETATE_TRY(out->warm_pipelines());
    if (options.gpu_timings) {
        // One mark per host step (the clear, each floor's tiles and composite, the output) and
        // one per effect pass.
        uint32_t marks = 2;
        for (const auto& floor : out->floor_effects_) {
            marks += 2;
            for (const auto& e : floor) marks += uint32_t(e->passes.size());
        }
        for (const auto& e : out->global_effects_) marks += uint32_t(e->passes.size());
        auto timer = GpuTimer::create(context, marks);
        if (timer)
            out->timer_ = std::move(timer.value());
        else
            out->timer_warning_ = timer.error().message;
    }

    const ResourceCounters used = delta(context.counters(), before);
    out->load_stats_ = {milliseconds_since(start), used.images_loaded,
                        used.targets_allocated,    used.shaders_compiled,
                        used.pipelines_created,    out->resources_->tile_texel_violations()};
    return out;
}

bool Compositor::needs_floor_target() const {
    bool any_effects = false;
    for (const LoadedFloor& f : resources_->floors()) any_effects |= f.geometry.needs_target;
    return any_effects || !options_.plan.draw_direct || view_reads_floor_target(options_.view) ||
           options_.inject.has_value();
}

Result<void> Compositor::create_targets(const SceneDesc& scene) {
    const std::string where = scene.file.string() + ": canvas";
    auto wrap = [&](Result<GpuImage> r) -> Result<GpuImage> {
        if (!r)
            return make_error(r.error().code, where + ": " + r.error().message,
                              r.error().vk_result);
        return r;
    };
    auto accumulation = wrap(GpuImage::create(context_, "accumulation", width_, height_,
                                              options_.format, kTargetUsage, true));
    if (!accumulation) return accumulation.error();
    accumulation_ = std::move(accumulation.value());
    auto output = wrap(
        GpuImage::create(context_, "output", width_, height_, options_.format, kTargetUsage, true));
    if (!output) return output.error();
    output_ = std::move(output.value());
    if (needs_floor_target()) {
        auto color = wrap(GpuImage::create(context_, "floor.color", width_, height_,
                                           options_.format, kTargetUsage, true));
        if (!color) return color.error();
        floor_color_ = std::move(color.value());
        auto stencil = wrap(GpuImage::create(
            context_, "floor.stencil", width_, height_, context_.stencil_format(),
            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, true));
        if (!stencil) return stencil.error();
        floor_stencil_ = std::move(stencil.value());
    }
    const bool floor_effects = std::any_of(floor_effects_.begin(), floor_effects_.end(),
                                           [](const auto& f) { return !f.empty(); });
    if (floor_effects) {
        auto pingpong = wrap(GpuImage::create(context_, "floor.pingpong", width_, height_,
                                              options_.format, kTargetUsage, true));
        if (!pingpong) return pingpong.error();
        floor_pingpong_ = std::move(pingpong.value());
    }
    if (!global_effects_.empty()) {
        auto pingpong = wrap(GpuImage::create(context_, "accumulation.pingpong", width_, height_,
                                              options_.format, kTargetUsage, true));
        if (!pingpong) return pingpong.error();
        accumulation_pingpong_ = std::move(pingpong.value());
    }
    auto violations = GpuBuffer::create(
        context_, VkDeviceSize(sizeof(uint32_t) * std::max<size_t>(1, scene.floors.size())),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!violations) return violations.error();
    violations_ = std::move(violations.value());
    return {};
}

// lavapipe compiles a pipeline's shaders at its first draw (30-100 ms each: docs/design.md,
// "Facts about lavapipe"), so every pipeline in use draws one pixel here and the first real
// frame does not stall (L-warm-switch).
Result<void> Compositor::warm_pipelines() {
    std::memset(violations_.mapped(), 0, violations_.size());
    // lavapipe keys its shader variants on texture and sampler state too (a power-of-two
    // texture and another size compile apart, nearest and linear too), so the tile stages draw
    // once with every distinct texture and the sampler each of its tiles is drawn with.
    std::vector<std::pair<const GpuImage*, VkSampler>> textures;
    for (const LoadedFloor& f : resources_->floors())
        for (const LoadedTile& t : f.tiles)
            if (const std::pair used{t.texture, pipelines_->tile_sampler(t.one_to_one)};
                std::find(textures.begin(), textures.end(), used) == textures.end())
                textures.push_back(used);
    const PixelRect pixel{0, 0, 1, 1};
    const bool has_depth = context_.stencil_format() != VK_FORMAT_S8_UINT;
    auto draw_one_pixel = [&](VkCommandBuffer cmd, HostPass stage, GpuImage& target, bool stencil,
                              VkImageView input, VkSampler tile_sampler = VK_NULL_HANDLE) {
        target.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        VkRenderingAttachmentInfo color = color_attachment(target.view(), true);
        VkRenderingAttachmentInfo stencil_info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = to_vk(pixel);
        info.layerCount = 1;
        info.colorAttachmentCount = 1;
        info.pColorAttachments = &color;
        if (stencil) {
            floor_stencil_->transition(cmd, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
            stencil_info.imageView = floor_stencil_->view();
            stencil_info.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
            stencil_info.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            stencil_info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            stencil_info.clearValue.depthStencil = {1.0f, 1};
            info.pStencilAttachment = &stencil_info;
            info.pDepthAttachment = has_depth ? &stencil_info : nullptr;
        }
        vkCmdBeginRendering(cmd, &info);
        set_scissor(cmd, pixel);
        // The same sampler as the real draws: lavapipe's shader variants depend on it too.
        const bool is_tile_stage =
            stage == HostPass::TileToTarget || stage == HostPass::TileToAccum;
        bind(cmd, stage, input, input,
             is_tile_stage ? tile_sampler : pipelines_->nearest_sampler());
        HostPassPushConstants push;
        push.rect[2] = push.rect[3] = 1;
        push.canvas[0] = float(width_);
        push.canvas[1] = float(height_);
        vkCmdPushConstants(cmd, pipelines_->layout(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        vkCmdDraw(cmd, is_tile_stage ? 4 : 3, 1, 0, 0);
        vkCmdEndRendering(cmd);
    };
    return context_.submit_and_wait([&](VkCommandBuffer cmd) {
        // Clearing every target whole makes the driver commit their memory now: on lavapipe
        // the first touch of a fresh 1080p target otherwise costs the first frame ~20 ms. It
        // also means no target ever holds what the allocation happened to contain: an effect
        // that reads a target it wrote only in part reads zeros (or the one pixel the warm-up
        // below draws), the same in every process.
        const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
        const VkImageSubresourceRange colour{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        std::vector<GpuImage*> targets = effect_targets_.images();
        for (auto* optional : {&floor_color_, &floor_pingpong_, &accumulation_pingpong_})
            if (optional->has_value()) targets.push_back(&optional->value());
        targets.push_back(&accumulation_);
        targets.push_back(&output_);
        for (GpuImage* target : targets) {
            target->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            vkCmdClearColorImage(cmd, target->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero,
                                 1, &colour);
        }
        if (floor_stencil_) {
            floor_stencil_->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            const VkClearDepthStencilValue clear{1.0f, 0};
            const VkImageSubresourceRange range{floor_stencil_->aspect(), 0, 1, 0, 1};
            vkCmdClearDepthStencilImage(cmd, floor_stencil_->image(),
                                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
        }
        // Inputs are sampled while another image is the attachment: the output is drawn with
        // the accumulation as input, everything else with a tile texture or the output.
        if (options_.plan.draw_direct)
            for (const auto& [texture, sampler] : textures)
                draw_one_pixel(cmd, HostPass::TileToAccum, accumulation_, false, texture->view(),
                               sampler);
        output_.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        if (floor_color_) {
            for (const auto& [texture, sampler] : textures)
                draw_one_pixel(cmd, HostPass::TileToTarget, *floor_color_, true, texture->view(),
                               sampler);
            if (options_.inject)
                draw_one_pixel(cmd, inject_stage(), *floor_color_, true, output_.view());
            draw_one_pixel(cmd, HostPass::Composite, accumulation_, true, output_.view());
            if (std::any_of(floor_effects_.begin(), floor_effects_.end(), [](const auto& f) {
                    return std::any_of(f.begin(), f.end(),
                                       [](const auto& e) { return e->expanding; });
                }))
                draw_one_pixel(cmd, HostPass::CompositeByAlpha, accumulation_, true,
                               output_.view());
        }
        accumulation_.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        draw_one_pixel(cmd, HostPass::Output, output_, false, accumulation_.view());
        // Every effect pass too, reading the (cleared) output and writing one pixel.
        auto warm_effect = [&](EffectInstance& effect, GpuImage& result) {
            EffectIo io;
            io.previous = &output_;
            io.result = &result;
            io.result_scissor = PixelRect{0, 0, 1, 1};
            io.canvas_width = width_;
            io.canvas_height = height_;
            io.warm_up = true;
            FloorFrameReport ignored;
            record_effect(cmd, renderer_, effect, io, ignored);
        };
        for (auto& floor : floor_effects_)
            for (auto& effect : floor) warm_effect(*effect, *floor_pingpong_);
        for (auto& effect : global_effects_) warm_effect(*effect, *accumulation_pingpong_);
        // Poisoned after the warm-up, which wrote a pixel of some targets: until an effect
        // writes it, every texel reads as the poison. Once only: what one floor or frame
        // wrote must stay for the next (a plugin reading it is then caught by the isolation
        // checks, not by the poison).
        if (options_.poison) {
            VkClearColorValue poison;
            std::memcpy(poison.float32, options_.poison->data(), sizeof(poison.float32));
            for (GpuImage* target : effect_targets_.images()) {
                target->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
                vkCmdClearColorImage(cmd, target->image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                     &poison, 1, &colour);
            }
        }
    });
}

}  // namespace acetate
