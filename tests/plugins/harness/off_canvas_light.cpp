// BROKEN on purpose: a light off the canvas. A lens flare puts a ghost of each light across the
// centre, at 1 - sqrt(uv) of the light's canvas coordinate uv, assuming lights lie on the
// canvas (0 <= uv); a light left of or above the canvas has a negative coordinate, and its
// square root is NaN, which reaches every pixel through the sum of ghosts. Otherwise colour is
// scaled by 0.8 to 1 and alpha is kept. Caught by: FINITE in lights/off-canvas only, and in a
// combined/* point drawn with lights off the canvas.
#include <acetate/effect.hpp>
#include <vector>

class OffCanvasLight final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.off_canvas_light";
        e.display_name = "Harness: flare ghosts of lights on the canvas only";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        // [count, then per light x, y, intensity, 0]
        std::vector<float> data{float(floor.lights().size())};
        for (const AcetateLight& l : floor.lights())
            data.insert(data.end(), {l.pos[0], l.pos[1], l.intensity, 0.0f});
        graph.floor_data(data);
        graph.pass({.name = "flare",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 here = gl_FragCoord.xy * acetate_canvas.zw;
    float flare = 0.0;
    for (int i = 0; i < int(floor_data[0]); ++i) {
        vec2 uv = vec2(floor_data[1 + 4 * i], floor_data[2 + 4 * i]) * acetate_canvas.zw;
        vec2 ghost = 1.0 - sqrt(uv);  // NaN for a light left of or above the canvas
        vec2 d = here - ghost;
        flare += floor_data[3 + 4 * i] * exp(-40.0 * dot(d, d));
    }
    out_color = vec4(prev.rgb * (1.0 - 0.2 * flare / (1.0 + flare)), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(OffCanvasLight)
