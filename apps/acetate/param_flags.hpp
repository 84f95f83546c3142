#pragma once
// `acetate render --param WHERE.NAME=VALUE` and `--preset WHERE=PRESET`: an effect's parameters
// set for the run without editing the scene file, through the API's live parameters
// (Scene::set_param, set_preset). WHERE is FLOOR.EFFECT: FLOOR a floor's name or index, or
// "global"; EFFECT the plugin id of an entry listed once there, or the entry's index. VALUE is
// a number, or 2 or 3 numbers joined by commas for a vector or colour; every number goes
// through the one reader.

#include <string>
#include <string_view>
#include <vector>

#include "acetate/host/host.hpp"
#include "core/result.hpp"

namespace acetate {

struct ParamFlag {
    std::string text;          // as given, for messages
    std::string flag;          // "--param" or "--preset"
    std::string floor;         // a floor's name or index, or "global"
    std::string effect;        // a plugin id or an index
    std::string name;          // --param: the parameter
    std::vector<float> value;  // --param: its components
    std::string preset;        // --preset
};

// Reads one --param (preset = false) or --preset. Errors are one line starting with the flag.
Result<ParamFlag> parse_param_flag(std::string_view text, bool preset);

// The effect a flag names in a scene; an error names the flag, the scene file and what is
// missing ("--param roofs.acetate.water.foam=1: scene.json has no floor \"roofs\" ...").
Result<host::EffectSlot> resolve_param_flag(const ParamFlag& flag, const host::SceneInfo& scene);

}  // namespace acetate
