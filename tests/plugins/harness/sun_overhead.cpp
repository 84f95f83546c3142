// BROKEN on purpose: a sun straight overhead. The sun's direction across the floor is taken as
// direction.xy / length(direction.xy), which a sun at elevation 90, as the format allows (its
// direction exactly (0, 0, 1)), makes 0 / 0 = NaN. Otherwise colour is scaled by 0.8 to 0.9
// by how far the sun's direction points along +x, and alpha is kept.
// Caught by: FINITE in lights/zenith-sun only, and in a combined/* point drawn with it.
#include <acetate/effect.hpp>

class SunOverhead final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.sun_overhead";
        e.display_name = "Harness: the sun's direction across the floor";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "across",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float along = 0.0;
    for (int i = 0; i < int(acetate_light_count); ++i)
        if (acetate_lights[i].kind == ACETATE_LIGHT_SUN) {
            vec2 across = acetate_lights[i].direction.xy;
            along = (across / length(across)).x;
        }
    out_color = vec4(prev.rgb * (0.85 + 0.05 * along), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(SunOverhead)
