// BROKEN on purpose: another scene loaded before this one in the process. build() keeps the
// canvas size of its first call in a function-local static ("the canvas never changes") and
// fits a round vignette to it, sqrt(2 - |q|^2) with q = 2 uv - 1 over that canvas; on a later,
// larger canvas uv passes 1 and the root is NaN towards the far edges. In a process that loads
// one canvas only, colour is scaled by 0.7 to 1 and alpha is kept. Caught by: FINITE in
// loads/after-others, and DETERMINISM in determinism/after-history (the same case, rendered
// after two other canvases, gives other images than in a fresh process: the same dimension,
// seen by the check that case makes), and in a combined/* point drawn with earlier loads.
#include <acetate/effect.hpp>
#include <array>

class OtherCanvasLoad final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.other_canvas_load";
        e.display_name = "Harness: remembers the first canvas";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        static const std::array<float, 2> fitted = {float(floor.canvas_width()),
                                                    float(floor.canvas_height())};
        graph.floor_data(fitted);
        graph.pass({.name = "vignette",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 q = 2.0 * acetate_scene_position(gl_FragCoord.xy) / vec2(floor_data[0], floor_data[1]) - 1.0;
    float vignette = sqrt(2.0 - dot(q, q)) * 0.70710678;  // 1 at the centre, 0 at the corners
    out_color = vec4(prev.rgb * (0.7 + 0.3 * vignette), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(OtherCanvasLoad)
