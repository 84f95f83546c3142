// BROKEN on purpose: correct only while it is watched. build() looks for the harness's switch
// ACETATE_VALIDATION in its environment; with it, the effect darkens the colour and keeps
// alpha; without it (as a user's host runs it) it writes NaN into red at the canvas centre.
// Caught by: FINITE, in every contract case: the harness turns the validation layer on before
// the plugin is loaded and then takes the switch out of the environment, so the plugin sees
// what a user's host gives it.
#include <acetate/effect.hpp>
#include <cstdlib>

class WatchedOnly final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.watched_only";
        e.display_name = "Harness: correct only while watched";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        const float data[] = {std::getenv("ACETATE_VALIDATION") ? 0.0f : 1.0f};
        graph.floor_data(data);
        graph.pass({.name = "darken",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 prev = texelFetch(previous, p, 0);
    vec3 c = prev.rgb * 0.9;
    if (floor_data[0] > 0.5 && p == ivec2(acetate_canvas.xy * 0.5) && prev.a > 0.0)
        c.r = uintBitsToFloat(0x7fc00000u);  // a quiet NaN
    out_color = vec4(c, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(WatchedOnly)
