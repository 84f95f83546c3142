#include "scene_variants.hpp"

#include <algorithm>

namespace acetate::bench {
namespace {

template <typename Fn>
void for_each_effect_list(SceneDesc& scene, Fn&& fn) {
    for (FloorDesc& floor : scene.floors) fn(floor.effects);
    fn(scene.global_effects);
}

}  // namespace

std::set<std::string> plugins_named(const SceneDesc& scene) {
    std::set<std::string> ids;
    SceneDesc copy = scene;
    for_each_effect_list(copy, [&](std::vector<EffectRef>& effects) {
        for (const EffectRef& e : effects) ids.insert(e.plugin);
    });
    return ids;
}

SceneDesc with_preset(SceneDesc scene, const std::string& plugin, const std::string& preset) {
    for_each_effect_list(scene, [&](std::vector<EffectRef>& effects) {
        for (EffectRef& e : effects)
            if (e.plugin == plugin) e.preset = preset;
    });
    return scene;
}

SceneDesc without_plugin(SceneDesc scene, const std::string& plugin) {
    for_each_effect_list(scene, [&](std::vector<EffectRef>& effects) {
        std::erase_if(effects, [&](const EffectRef& e) { return e.plugin == plugin; });
    });
    return scene;
}

SceneDesc without_effects(SceneDesc scene) {
    for_each_effect_list(scene, [](std::vector<EffectRef>& effects) { effects.clear(); });
    return scene;
}

}  // namespace acetate::bench
