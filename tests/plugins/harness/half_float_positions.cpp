// BREAKS the format-agreement relation: it keeps pixel positions in an intermediate target of
// the floor's format, where rgba16f cannot hold them (past 1024 a half float steps by 1, past
// 2048 by 2), then shades with the positions it reads back. In rgba32f the positions are
// exact, so the two formats disagree on a wide canvas; a correct effect declares such a target
// ACETATE_FORMAT_RG32F. Every output is valid on its own: the colour is scaled by a factor in
// [0.5, 1] and alpha kept. Caught by `format-agreement` in formats/rgba32f only.
#include <acetate/effect.hpp>

class HalfFloatPositions final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.half_float_positions";
        e.display_name = "Harness battery: positions kept in the floor's format";
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"ripple", "how strongly the stripes darken", 0.5f, 0.1f, 0.5f}};
        // At scale 1/2 a pixel's centre is a scene pixel's corner: a stripe's crest between two
        // pixel centres lies above both (by about ripple * 0.5 * (1 - cos 0.2), under 1 %).
        e.scale_tolerance = 0.05f;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.target("positions", 1);  // the floor's format: the mistake
        graph.pass({.name = "positions",
                    .glsl = R"(
void main() { out_color = vec4(acetate_scene_position(gl_FragCoord.xy), 0.0, 1.0); }
)",
                    .output = "positions"});
        graph.pass({.name = "stripes",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 prev = texelFetch(previous, p, 0);
    float x = texelFetch(positions, p, 0).x;
    float fade = 1.0 - param_ripple * (0.5 + 0.5 * sin(0.4 * x));
    out_color = vec4(prev.rgb * fade, prev.a);
}
)",
                    .inputs = {"previous", "positions"}});
    }
};
ACETATE_REGISTER_EFFECT(HalfFloatPositions)
