// Live parameters: an effect's entry changed after load (other params, another preset). The
// plugin's build() runs again with the new values; when it declares exactly the graph it
// declared before (effect_graph_digest), the values reach the next frame through the uniforms
// each frame writes anyway, and nothing is allocated, loaded or compiled. A different graph
// (another number of passes, other floor data, another reach) replaces that one instance whole:
// its passes compiled (or found in the pool), its targets and buffers made, the planner's
// areas made again for a new reach, every pipeline warmed as at load. Only a graph that
// changes what the load chose around the effect (its coverage, whether it declares anything)
// is left to the caller, which loads the scene again.
#include <fmt/format.h>

#include "render/compositor.hpp"
#include "render/renderer.hpp"

namespace acetate {

Result<EffectRef> Compositor::effect_ref(std::optional<uint32_t> floor, uint32_t index) const {
    const std::string file = scene_.file.string();
    if (floor && *floor >= scene_.floors.size())
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: floor {} does not exist (floors 0..{})", file, *floor,
                                      scene_.floors.size() - 1));
    const std::vector<EffectRef>& refs =
        floor ? scene_.floors[*floor].effects : scene_.global_effects;
    if (index >= refs.size())
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{}: {}: no effect {} (it lists {})", file,
                        floor ? fmt::format("floors[{}].effects", *floor) : "global_effects", index,
                        refs.size()));
    return refs[index];
}

Compositor::EffectPosition Compositor::effect_position(std::optional<uint32_t> floor,
                                                       uint32_t index) const {
    EffectPosition position;
    const auto& instances = floor ? floor_effects_.at(*floor) : global_effects_;
    for (const auto& instance : instances) {
        if (instance->scene_index < index) ++position.before;
        if (instance->scene_index == index) position.runs = true;
    }
    return position;
}

Result<Compositor::EffectChange> Compositor::set_effect_ref(std::optional<uint32_t> floor,
                                                            uint32_t index, const EffectRef& ref) {
    auto current = effect_ref(floor, index);
    if (!current) return current.error();
    std::vector<EffectRef>& refs = floor ? scene_.floors[*floor].effects : scene_.global_effects;
    EffectRef updated = ref;
    updated.plugin = refs[index].plugin;  // the effect is changed, never swapped
    updated.where = refs[index].where;

    InstanceSetup setup;
    setup.format = options_.format;
    setup.checked_builtins = options_.checked_builtins;
    setup.view = view_;
    auto plugin = renderer_.plugins().load(updated.plugin);  // loaded already: a lookup
    if (!plugin) return plugin.error();
    if (floor && !plugin.value()->descriptor.masks.empty()) {
        // build() may read its floor's masks (read_mask): the same composites the load made.
        if (!live_masks_) {
            auto masks = composite_scene_masks(scene_, options_.mask_kinds);
            if (!masks) return masks.error();
            live_masks_ = std::move(masks.value());
        }
        setup.masks = &live_masks_->floors[*floor];
    }
    auto prepared =
        prepare_effect_instance(renderer_, scene_, updated, floor ? int64_t(*floor) : -1, setup);
    if (!prepared) return prepared.error();

    auto& instances = floor ? floor_effects_[*floor] : global_effects_;
    for (auto& instance : instances) {
        if (instance->scene_index != index) continue;
        if (instance->graph_digest == prepared->instance->graph_digest) {
            instance->params = prepared->instance->params;
            refs[index] = std::move(updated);
            return EffectChange::Values;
        }
        // The floor's targets and host passes were chosen for this coverage, and for an
        // effect that runs; another reach only moves the planner's areas (planned again).
        const EffectInstance& next = *prepared->instance;
        if (next.expanding != instance->expanding || prepared->graph.passes.empty())
            return EffectChange::NeedsLoad;
        const bool reach_changed = next.reach != instance->reach;
        setup.targets = &targets_.effect_targets();
        auto created =
            create_effect_instance(renderer_, scene_, updated, floor ? int64_t(*floor) : -1, setup,
                                   std::move(prepared.value()));
        if (!created) return created.error();
        created.value()->scene_index = index;
        bind_masks(*created.value(), floor);
        // The frames before used the old instance's buffers: they are finished (every frame
        // is waited for), so it can go now.
        instance = std::move(created.value());
        invalidate_frames();  // they named the old instance's passes and targets
        refs[index] = std::move(updated);
        if (reach_changed) plan_geometry(scene_);
        // As at load: every pipeline draws once (lavapipe compiles at the first draw) and
        // every target starts cleared, so the next frame compiles nothing.
        ACETATE_TRY(warm_pipelines());
        if (timer_) create_timer();  // one mark per pass: the count may have changed
        return EffectChange::Rebuilt;
    }
    return EffectChange::NeedsLoad;  // dropped at load (it declared nothing there)
}

}  // namespace acetate
