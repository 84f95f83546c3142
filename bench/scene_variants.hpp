#pragma once
// The scenes acetate-bench renders, derived from the one the user gave: the same floors, tiles
// and lights, with one plugin's instances set to a preset or taken out, or every effect taken
// out (what another tool would flatten). Pure data: nothing here loads or renders.

#include <set>
#include <string>

#include "scene/scene.hpp"

namespace acetate::bench {

// The plugin ids a scene names, floors and global effects alike, sorted.
std::set<std::string> plugins_named(const SceneDesc& scene);

// Every instance of `plugin` takes `preset` (empty: the plugin's defaults, no preset); the
// other effects keep what the scene gave them.
SceneDesc with_preset(SceneDesc scene, const std::string& plugin, const std::string& preset);

// Every instance of `plugin` removed: the frame without that effect, for its own share.
SceneDesc without_plugin(SceneDesc scene, const std::string& plugin);

// Every effect removed, floors and global: plain layer flattening.
SceneDesc without_effects(SceneDesc scene);

}  // namespace acetate::bench
