// BROKEN on purpose: the canvas's parity. A "lens" shading lights the floor from the right by
// the direction from the canvas centre, but the centre is put half a pixel low,
// c = (w / 2, h / 2 + 0.5) (the author converted from a y-up convention), so it falls exactly on
// a pixel centre when the width is odd and the height even; there normalize(p - c) is
// normalize(vec2(0)), NaN. Everywhere else colour is scaled by 0.8 to 1 and alpha is kept.
// Caught by: FINITE in sizes/odd-even (37x24) only, and in any combined/* point drawn with an
// odd width and an even height.
#include <acetate/effect.hpp>

class OddWidthEvenHeight final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.odd_width_even_height";
        e.display_name = "Harness: NaN at the centre of odd x even canvases";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "lens",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    // Half a pixel low: a pixel centre when the width is odd and the height even.
    vec2 centre = vec2(0.5 * acetate_canvas.x, 0.5 * acetate_canvas.y + 0.5);
    vec2 towards = normalize(gl_FragCoord.xy - centre);  // NaN at the centre itself
    out_color = vec4(prev.rgb * (0.9 + 0.1 * towards.x), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(OddWidthEvenHeight)
