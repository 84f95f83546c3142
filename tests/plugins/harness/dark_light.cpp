// BROKEN on purpose: a light of colour 0. Each point light's hue is its colour over its
// brightest channel, c / max(r, g, b), which a light of colour (0, 0, 0), as the format allows,
// makes 0 / 0 = NaN. Otherwise colour is tinted by 0.9 to 1 and alpha is kept.
// Caught by: FINITE in lights/dark only, and in a combined/* point drawn with it.
#include <acetate/effect.hpp>

class DarkLight final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.dark_light";
        e.display_name = "Harness: a light's hue from its colour";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "hue",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec3 hue = vec3(1.0);
    for (int i = 0; i < int(acetate_light_count); ++i)
        if (acetate_lights[i].kind == ACETATE_LIGHT_POINT) {
            vec3 c = acetate_lights[i].color;
            hue *= 0.9 + 0.1 * c / max(c.r, max(c.g, c.b));
        }
    out_color = vec4(prev.rgb * hue, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(DarkLight)
