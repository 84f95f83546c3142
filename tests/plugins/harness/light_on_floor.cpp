// BROKEN on purpose: a light on the floor. Each point light spreads its glow by radius / height
// ("taller lights reach wider"), which a light at height exactly 0, as the format allows, makes
// infinite, and the glow's compression inf / (1 + inf) is NaN. Otherwise colour is scaled by
// 0.8 to 1 and alpha is kept.
// Caught by: FINITE in lights/on-the-floor only, and in a combined/* point drawn with it.
#include <acetate/effect.hpp>

class LightOnFloor final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.light_on_floor";
        e.display_name = "Harness: divides by a light's height";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "spread",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float spread = 0.0;
    for (int i = 0; i < int(acetate_light_count); ++i)
        if (acetate_lights[i].kind == ACETATE_LIGHT_POINT)
            spread += acetate_lights[i].radius / acetate_lights[i].height;
    out_color = vec4(prev.rgb * (0.8 + 0.2 * spread / (1.0 + spread)), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(LightOnFloor)
