// Live parameters: an effect's entry changed after load (other params, another preset). The
// plugin's build() runs again with the new values; when it declares exactly the graph it
// declared before (effect_graph_digest), the values reach the next frame through the uniforms
// each frame writes anyway, and nothing is allocated, loaded or compiled. A different graph
// (another number of passes, other floor data) is left to the caller, which loads the scene
// again: this file never half-replaces an instance.
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

Result<bool> Compositor::set_effect_ref(std::optional<uint32_t> floor, uint32_t index,
                                        const EffectRef& ref) {
    auto current = effect_ref(floor, index);
    if (!current) return current.error();
    std::vector<EffectRef>& refs = floor ? scene_.floors[*floor].effects : scene_.global_effects;
    EffectRef updated = ref;
    updated.plugin = refs[index].plugin;  // the effect is changed, never swapped
    updated.where = refs[index].where;

    InstanceSetup setup;
    setup.format = options_.format;
    setup.checked_builtins = options_.checked_builtins;
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
        if (instance->graph_digest != prepared->instance->graph_digest) return false;
        instance->params = prepared->instance->params;
        refs[index] = std::move(updated);
        return true;
    }
    return false;  // dropped at load (it declared nothing there): only a load can add it
}

}  // namespace acetate
