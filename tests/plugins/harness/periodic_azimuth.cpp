// CORRECT (a control): a periodic parameter. `azimuth` (0..360 degrees, default 45) turns a
// shading direction around the circle, so 0 and 360 are the same direction and give the same
// output bit for bit (the shader wraps with mod(azimuth, 360)), while 90, 180 and 270 differ.
// out.rgb = prev.rgb * (0.75 + 0.25 * cos(azimuth)), alpha kept.
// Must pass every check: `disconnected-parameters` judges a parameter over its whole range,
// not only between its ends (the check's message names azimuth as periodic).
#include <acetate/effect.hpp>

class PeriodicAzimuth final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.periodic_azimuth";
        e.display_name = "Harness: periodic azimuth";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"azimuth", "direction of the shading, degrees", 45.0f, 0.0f, 360.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "shade",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float turn = radians(mod(param_azimuth, 360.0));
    out_color = vec4(prev.rgb * (0.75 + 0.25 * cos(turn)), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(PeriodicAzimuth)
