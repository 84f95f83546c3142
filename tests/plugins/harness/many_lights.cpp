// BROKEN on purpose: the floor's lights, more of them than it was written for. build() packs
// them into a fixed std::array of 64 with at(), which throws std::out_of_range for the 65th, so
// the load fails (a plugin should cap its lights, as acetate.lighting's presets do). With 64
// lights or fewer it tints the floor by their average colour (alpha kept). Caught by: the LOAD
// check in lights/many (100 lights) only, and in a combined/* point drawn with many lights; the
// message names std::array's bound, 64.
#include <acetate/effect.hpp>
#include <array>
#include <vector>

class ManyLights final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.many_lights";
        e.display_name = "Harness: room for 64 lights";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        struct Packed {
            float intensity, r, g, b;
        };
        std::array<Packed, 64> lights{};
        size_t count = 0;
        for (const AcetateLight& l : floor.lights())
            lights.at(count++) = {l.intensity, l.color[0], l.color[1], l.color[2]};  // throws
        std::vector<float> data{float(count)};
        for (size_t i = 0; i < count; ++i)
            data.insert(data.end(), {lights[i].intensity, lights[i].r, lights[i].g, lights[i].b});
        graph.floor_data(data);
        graph.pass({.name = "tint",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    int count = int(floor_data[0]);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < count; ++i)
        sum += floor_data[1 + 4 * i] * vec3(floor_data[2 + 4 * i], floor_data[3 + 4 * i],
                                            floor_data[4 + 4 * i]);
    vec3 average = sum / float(count > 0 ? count : 1);
    out_color = vec4(prev.rgb * (0.75 + 0.25 * average / (1.0 + average)), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(ManyLights)
