// BROKEN on purpose: a floor without tiles. build() sizes a vignette by the aspect of the
// floor's coverage bounds in whole percent, 100 * width / height in integers, which a floor
// without any tile (bounds all 0, as the format allows) makes an integer division by zero:
// SIGFPE. Otherwise colour is scaled by 0.8 to 1 towards the bounds' edges and alpha is kept.
// Caught by: CRASH in floors/top-floor-empty only, and in a combined/* point drawn with it.
#include <acetate/effect.hpp>

class EmptyFloorBounds final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.empty_floor_bounds";
        e.display_name = "Harness: a vignette by the coverage bounds' aspect";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        const acetate::sdk::Bounds b = floor.coverage_bounds();
        const int width = b.x1 - b.x0, height = b.y1 - b.y0;
        const int aspect_percent = 100 * width / height;  // no tiles: 0 / 0 in integers
        const float data[] = {float(b.x0), float(b.y0), float(width),
                              float(width) * 100.0f / float(aspect_percent)};
        graph.floor_data(data);
        graph.pass({.name = "vignette",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 at = (acetate_scene_position(gl_FragCoord.xy) - vec2(floor_data[0], floor_data[1])) /
              vec2(floor_data[2], floor_data[3]);
    float edge = length(at - 0.5);
    out_color = vec4(prev.rgb * (1.0 - 0.2 * edge / (1.0 + edge)), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(EmptyFloorBounds)
