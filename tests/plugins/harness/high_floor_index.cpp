// BROKEN on purpose: the floor the plugin is on. An atmospheric haze that thickens with height,
// written for buildings of at most three floors (ground, first, roof): the height fraction
// h = floor / 3 reaches 1 on floor 3, where the haze 0.1 h / sqrt(1 - h) is infinite, and is NaN
// above (the square root of a negative number). On floors 0 to 2 colour is scaled by 0.88 to 1
// and alpha is kept. Caught by: FINITE in floors/top-of-five (the plugin on floor 4) and
// floors/eight (floors 3 to 7) only, and in a combined/* point with four floors.
#include <acetate/effect.hpp>

class HighFloorIndex final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.high_floor_index";
        e.display_name = "Harness: haze for three floors at most";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "haze",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float h = float(acetate_floor) / 3.0;  // 0 on the ground, 1 on the roof (floor 3: wrong)
    float haze = 0.1 * h * inversesqrt(1.0 - h);
    out_color = vec4(prev.rgb * (1.0 - haze), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(HighFloorIndex)
