#pragma once
// One effect instance's declared work, as build() declared it through the AcetateHostApi:
// targets, passes in order, and floor data. Every declaration is checked as it is made, so the
// whole frame is valid before anything runs; errors name the instance, pass and resource, e.g.
// `pass "floor2.acetate.bloom.down3" reads "down2", which no earlier pass writes`.

#include <acetate/effect.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "plugins/plugin_loader.hpp"
#include "scene/floor_masks.hpp"

namespace acetate {

struct GraphTarget {
    std::string name;
    uint32_t divisor = 1;
    uint32_t format = ACETATE_FORMAT_FLOOR;  // ACETATE_FORMAT_*
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
    std::vector<std::string> input_names;  // the GLSL name of each input (1.1: may be chosen)
    std::string defines;                   // "#define" lines placed before the GLSL (1.1)
};

// A periodic phase the plugin declared (1.1): GLSL phase_<name> = fract(time / period).
struct GraphPhase {
    std::string name;
    double period = 1;
};

struct GraphTexture {
    std::string name;
    uint32_t width = 0, height = 0;
    std::vector<float> texels;  // `channels` floats per texel
    uint32_t format = ACETATE_FORMAT_FLOOR;
    uint32_t channels = 4;  // 1, 2 or 4, as the format has
};

// Channels of an ACETATE_FORMAT_* (FLOOR: 4).
uint32_t format_channels(uint32_t format);

struct EffectGraph {
    std::vector<GraphTarget> targets;
    std::vector<GraphPass> passes;
    std::vector<GraphTexture> textures;
    std::vector<float> floor_data;
    std::vector<std::string> log;
    std::vector<GraphPhase> phases;
    std::optional<uint32_t> reach;  // set_reach (1.1); none: a expanding effect may reach anywhere
};

// What build() may look at besides AcetateFloorInfo, and what the device allows.
struct GraphContext {
    const FloorMasks* masks = nullptr;  // the floor's composites (read_mask); null: none
    uint32_t canvas_width = 0, canvas_height = 0;
    // Why the device cannot use `format` (ACETATE_FORMAT_*) as a target, or blend onto it when
    // `blend`; "" when it can. Unset: every format is usable (tests without a device).
    std::function<std::string(uint32_t format, bool blend)> format_problem;
};

// The default GLSL name of an input: '.' becomes '_' ("mask.water" -> "mask_water").
std::string input_variable(const std::string& input);

// The name of an ACETATE_FORMAT_* value ("RG16F"), or "" for an unknown one.
std::string format_name(uint32_t format);

// A digest of everything the graph declares (targets, passes with their code, textures with
// their texels, floor data, phases, reach), not its log: two builds with equal digests need the
// same GPU objects, so only the parameter values can differ between them.
std::string effect_graph_digest(const EffectGraph& graph);

// Calls the plugin's build() for one instance and returns what it declared, checked.
// `label` names the instance in errors ("floor2.acetate.lighting", "global.acetate.bloom").
Result<EffectGraph> build_effect_graph(const LoadedPlugin& plugin, const AcetateFloorInfo& floor,
                                       const std::string& label, const GraphContext& context = {});

}  // namespace acetate
