// acetate.lighting -- a floor effect: ambient light with a day/night level, the floor's own
// point lights from the scene, and a darkness level. Coverage-preserving.

#include <acetate/effect.hpp>
#include <vector>

#include "lighting_shaders.hpp"

namespace {

class Lighting final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "acetate.lighting";
        e.display_name = "Lighting";
        e.scope = ACETATE_SCOPE_FLOOR;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {
            {"day", "0 = night, 1 = full day: blends the two ambient levels", 1.0f, 0.0f, 1.0f},
            {"day_ambient", "ambient light level by day", 1.0f, 0.0f, 2.0f},
            {"night_ambient", "ambient light level by night", 0.15f, 0.0f, 2.0f},
            {"darkness", "dims ambient and point lights alike (0 = none, 1 = black)", 0.0f, 0.0f,
             1.0f},
            {"flicker", "how much point lights flicker with time", 0.0f, 0.0f, 1.0f},
            {"max_lights", "point lights considered per floor", 16.0f, 0.0f, 64.0f,
             ACETATE_PARAM_INT},
        };
        e.presets = {{"low", {{"max_lights", 4}}},
                     {"medium", {{"max_lights", 8}}},
                     {"high", {{"max_lights", 16}}},
                     {"ultra", {{"max_lights", 64}}}};
        return e;
    }

    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        // The floor's lights, prepared once at load: the shader loops over them per pixel.
        std::vector<float> data{float(floor.lights().size())};
        for (const AcetateLight& l : floor.lights()) {
            data.insert(data.end(), {l.pos[0], l.pos[1], l.radius, l.intensity, l.color[0],
                                     l.color[1], l.color[2], 0.0f});
        }
        graph.floor_data(data);
        graph.pass({.name = "light",
                    .glsl = std::string(lighting_frag),
                    .inputs = {"previous"},
                    .output = "result"});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(Lighting)
