// Compositor::load and what it does once per scene: plugins built into effect instances (and
// those that declared nothing dropped), masks, targets, pipelines compiled (and warmed, in
// compositor_warm_up.cpp), the planner's geometry. Frames are recorded in floor_recording.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <set>

#include "core/elapsed.hpp"
#include "render/compositor.hpp"  // the class whose loading half this is
#include "render/renderer.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {

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
    setup.targets = &targets_.effect_targets();
    setup.checked_builtins = options_.checked_builtins;
    setup.view = view_;
    floor_effects_.resize(scene.floors.size());
    for (size_t f = 0; f < scene.floors.size(); ++f) {
        setup.masks = &masks->floors[f];
        for (size_t i = 0; i < scene.floors[f].effects.size(); ++i) {
            const EffectRef& ref = scene.floors[f].effects[i];
            auto instance = create_effect_instance(renderer_, scene, ref, int64_t(f), setup);
            if (!instance && leave_out(instance.error(), uint32_t(f), i, ref)) continue;
            if (!instance) return instance.error();
            instance.value()->scene_index = i;
            // An instance that declared nothing (water on a floor without water) is dropped:
            // the floor then renders exactly as if the scene had not listed the effect.
            if (instance.value()->passes.empty()) continue;
            floor_effects_[f].push_back(std::move(instance.value()));
        }
    }
    setup.masks = nullptr;
    for (size_t i = 0; i < scene.global_effects.size(); ++i) {
        auto instance =
            create_effect_instance(renderer_, scene, scene.global_effects[i], -1, setup);
        if (!instance && leave_out(instance.error(), std::nullopt, i, scene.global_effects[i]))
            continue;
        if (!instance) return instance.error();
        instance.value()->scene_index = i;
        if (instance.value()->passes.empty()) continue;
        global_effects_.push_back(std::move(instance.value()));
    }
    return masks;
}

bool Compositor::leave_out(const Error& error, std::optional<uint32_t> floor, size_t index,
                           const EffectRef& ref) {
    if (!options_.leave_out_refused || error.code != ErrorCode::PluginRefused) return false;
    left_out_.push_back({floor, uint32_t(index), ref.plugin, error.message});
    return true;
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
    out->view_ = ViewTransform::whole(scene.width, scene.height);
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
    for (uint32_t f = 0; f < out->floor_effects_.size(); ++f)
        for (auto& effect : out->floor_effects_[f]) out->bind_masks(*effect, f);
    for (auto& effect : out->global_effects_) out->bind_masks(*effect, std::nullopt);
    ACETATE_TRY(out->targets_.allocate(context, out->width_, out->height_, options.format,
                                       out->target_needs(), scene.file.string() + ": canvas"));
    ACETATE_TRY(out->ensure_host_pipelines());
    out->plan_geometry(scene);
    ACETATE_TRY(out->warm_pipelines());
    if (options.gpu_timings) out->create_timer();
    // Every active floor's frame in the view loaded with, compiled now: a frame only runs one.
    for (uint32_t f = 0; f < out->floor_count(); ++f) ACETATE_TRY(out->frame_for(f));

    const ResourceCounters used = context.counters() - before;
    out->load_stats_ = {milliseconds_since(start), used.images_loaded,
                        used.targets_allocated,    used.shaders_compiled,
                        used.pipelines_created,    out->resources_->tile_texel_violations()};
    return out;
}

void Compositor::bind_masks(EffectInstance& instance, std::optional<uint32_t> floor) const {
    const GpuImage& blank_texture = renderer_.effect_pipelines().blank_texture();
    if (!floor) return bind_pass_masks(instance, nullptr, blank_texture);
    if (!view_masks_.empty())  // a camera: the masks in render pixels (view_masks())
        return bind_pass_masks(instance, &view_masks_[*floor], *view_blank_mask_);
    const GpuImage* blank_mask = resources_->blank_mask();
    bind_pass_masks(instance, &resources_->floors()[*floor].masks,
                    blank_mask ? *blank_mask : blank_texture);
}

FrameTargetNeeds Compositor::target_needs() const {
    FrameTargetNeeds needs;
    for (const LoadedFloor& f : resources_->floors()) needs.floor_target |= f.geometry.needs_target;
    needs.floor_target |= !options_.plan.draw_direct || view_reads_floor_target(options_.view) ||
                          options_.inject.has_value();
    needs.floor_effects = std::any_of(floor_effects_.begin(), floor_effects_.end(),
                                      [](const auto& f) { return !f.empty(); });
    needs.global_effects = !global_effects_.empty();
    needs.floor_count = resources_->floors().size();
    needs.share_roles = options_.plan.share_targets;
    return needs;
}

// Only the passes this scene uses are compiled (once per process: the pool keeps them).
Result<void> Compositor::ensure_host_pipelines() {
    std::vector<HostPass> passes{HostPass::Output};
    if (options_.plan.draw_direct) passes.push_back(HostPass::TileToAccum);
    if (targets_.has(SharedRole::FloorColour)) {
        passes.push_back(HostPass::TileToTarget);
        passes.push_back(HostPass::Composite);
        for (uint32_t f = 0; f < floor_count(); ++f)
            if (expands(f)) passes.push_back(HostPass::CompositeByAlpha);
        if (options_.inject) passes.push_back(inject_pass());
    }
    for (HostPass pass : passes)
        ACETATE_TRY(pipelines_->ensure(view_variant(pass, options_.view == OutputView::Isolation),
                                       options_.format));
    return {};
}

// The planner's view of each floor in render pixels, made at load and again when the camera
// moves. A floor with a coverage-expanding effect may draw past its tiles (a glow): for
// planning it covers its tiles grown by the effects' declared reach, or the whole output when
// one declared none.
void Compositor::plan_geometry(const SceneDesc& scene) {
    invalidate_frames();  // compiled for the old areas
    geometry_.clear();
    tile_pixels_.clear();
    expansion_areas_.clear();  // planned again when a live change moves an effect's reach
    shading_rects_.clear();
    for (uint32_t f = 0; f < floor_count(); ++f) {
        const LoadedFloor& loaded = resources_->floors()[f];
        FloorGeometry geometry;
        geometry.needs_target = loaded.geometry.needs_target;
        std::vector<PixelRect> tiles;
        for (const LoadedTile& tile : loaded.tiles) {
            const PixelRect pixels =
                view_.covered(tile.rect.x, tile.rect.y, tile.rect.width, tile.rect.height);
            geometry.coverage = bounding_union(geometry.coverage, pixels);
            if (tile.opaque && !pixels.empty()) geometry.opaque.push_back(pixels);
            tiles.push_back(pixels);
        }
        const bool expanding = expands(f);
        expansion_areas_.push_back(expanding ? view_.touched(expansion_area(scene, f))
                                             : PixelRect{});
        if (expanding) geometry.coverage = expansion_areas_.back();
        // A floor whose tiles lie far apart (houses, trees) would shade their whole bounding
        // box in every effect pass; its exact union as a few rects, one draw each, does not.
        // Past a handful of rects the draws cost more than the pixels they save.
        constexpr size_t kMaxShadingRects = 16;
        std::vector<PixelRect> rects;
        if (!floor_effects_[f].empty() && !expanding) {
            rects = disjoint_union(tiles);
            if (rects.size() > kMaxShadingRects) rects.clear();
        }
        shading_rects_.push_back(std::move(rects));
        geometry_.push_back(std::move(geometry));
        tile_pixels_.push_back(std::move(tiles));
    }
}

// One mark per host step (the clear, each floor's tiles and composite, the output) and one per
// effect pass. A device without timestamps loads anyway, untimed, with a warning.
void Compositor::create_timer() {
    uint32_t marks = 2;
    for (const auto& floor : floor_effects_) {
        marks += 2;
        for (const auto& e : floor) marks += uint32_t(e->passes.size());
    }
    for (const auto& e : global_effects_) marks += uint32_t(e->passes.size());
    auto timer = GpuTimer::create(context_, marks);
    if (timer)
        timer_ = std::move(timer.value());
    else
        timer_warning_ = timer.error().message;
}

}  // namespace acetate
