// BROKEN on purpose: the floor's lights, none of them. It tints the floor by the average colour
// of its lights, sum / count, and a floor without lights gives 0 / 0 = NaN. Lights are packed
// as acetate.lighting packs them; the tint lies in (0.75, 1], alpha is kept. Caught by: FINITE
// in lights/none only, and in a combined/* point drawn without lights.
#include <acetate/effect.hpp>
#include <vector>

class NoLights final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.no_lights";
        e.display_name = "Harness: divides by the light count";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        // [count, then per light x, y, radius, intensity, r, g, b, 0]
        std::vector<float> data{float(floor.lights().size())};
        for (const AcetateLight& l : floor.lights())
            data.insert(data.end(), {l.pos[0], l.pos[1], l.radius, l.intensity, l.color[0],
                                     l.color[1], l.color[2], 0.0f});
        graph.floor_data(data);
        graph.pass({.name = "tint",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    int count = int(floor_data[0]);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < count; ++i) {
        int at = 1 + 8 * i;
        vec3 colour = vec3(floor_data[at + 4], floor_data[at + 5], floor_data[at + 6]);
        sum += floor_data[at + 3] * colour;
    }
    vec3 average = sum / float(count);  // no lights: 0 / 0
    out_color = vec4(prev.rgb * (0.75 + 0.25 * average / (1.0 + average)), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(NoLights)
