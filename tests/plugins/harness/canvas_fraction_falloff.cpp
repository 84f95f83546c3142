// BREAKS the canvas-size relation: its falloff is measured in fractions of the canvas (uv
// coordinates), not in scene pixels, so the same floor darkens differently on a larger canvas
// (a scene grown for a wider shot, a host's larger view). Every output is valid on its own: the
// colour is scaled by a factor in [0.5, 1] and alpha kept. Caught by `canvas-size` in
// relations/canvas-size only.
#include <acetate/effect.hpp>

class CanvasFractionFalloff final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.canvas_fraction_falloff";
        e.display_name = "Harness battery: a falloff in fractions of the canvas";
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"depth", "how dark the falloff gets", 0.5f, 0.1f, 0.5f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "falloff",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 uv = gl_FragCoord.xy * acetate_canvas.zw;
    float fade = 1.0 - param_depth * clamp(length(uv - vec2(0.25)), 0.0, 1.0);
    out_color = vec4(prev.rgb * fade, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(CanvasFractionFalloff)
