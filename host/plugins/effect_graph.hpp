#pragma once
// One effect instance's declared work, as build() declared it through the AcetateHostApi:
// targets, passes in order, and floor data. Every declaration is checked as it is made, so the
// whole frame is valid before anything runs; errors name the instance, pass and resource, e.g.
// `pass "floor2.acetate.bloom.down3" reads "down2", which no earlier pass writes`.

#include <acetate/effect.h>

#include <string>
#include <vector>

#include "core/result.hpp"
#include "plugins/plugin_loader.hpp"

namespace acetate {

struct GraphTarget {
    std::string name;
    uint32_t divisor = 1;
};

struct GraphPass {
    std::string name;
    std::string glsl;             // the plugin's part (the host adds its declarations)
    std::vector<uint32_t> spirv;  // or a complete module
    std::vector<std::string> inputs;
    std::string output;  // "result" or a target name
    uint32_t blend = ACETATE_BLEND_REPLACE;
    uint32_t kind = ACETATE_PASS_FULLSCREEN;
    uint32_t instance_count = 0;  // instanced quads
    uint32_t instance_data_offset = 0;
};

struct GraphTexture {
    std::string name;
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
};

struct EffectGraph {
    std::vector<GraphTarget> targets;
    std::vector<GraphPass> passes;
    std::vector<GraphTexture> textures;
    std::vector<float> floor_data;
    std::vector<std::string> log;
};

// Calls the plugin's build() for one instance and returns what it declared, checked.
// `label` names the instance in errors ("floor2.acetate.lighting", "global.acetate.bloom").
Result<EffectGraph> build_effect_graph(const LoadedPlugin& plugin, const AcetateFloorInfo& floor,
                                       const std::string& label);

}  // namespace acetate
