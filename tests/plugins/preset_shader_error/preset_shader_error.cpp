// Its default pass compiles; the pass its "ultra" preset chooses has a GLSL error on line 4 of
// fancy.frag. `acetate check-shaders` must find it (it tries every preset) and name the file and
// line (tests/e2e/check_shaders_test.cpp).
#include <acetate/effect.hpp>

#include "preset_shader_error_shaders.hpp"

namespace {

using namespace acetate::sdk;

inline constexpr BoolParam kFancy{"fancy", "use the fancy pass", false};

class PresetShaderError final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "test.preset_shader_error";
        e.params = {kFancy};
        e.presets = quality_presets({{kFancy, {false, false, false, true}}});
        return e;
    }
    void build(Graph& graph, const Floor& floor) const override {
        const bool fancy = floor[kFancy];
        graph.pass({.name = fancy ? "fancy" : "plain",
                    .glsl = std::string(fancy ? fancy_frag : plain_frag),
                    .inputs = {"previous"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(PresetShaderError)
