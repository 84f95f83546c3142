// CONTROL: breaks no rule. Every harness check must pass, the integration `reference` included.
// A coverage-expanding drop shadow: the floor's own alpha, moved by kOffset pixels, is laid
// UNDER the floor as black at `opacity`:
//   out = prev + (1 - prev.a) * opacity * prev.a(p - offset) * (0, 0, 0, 1)
// so alpha only grows, rgb is the input's (still premultiplied, 0 wherever the input was
// transparent: the shadow adds alpha, never colour), and `opacity` changes every pixel the
// shadow reaches. On the HDR inputs it is what tripped the reference's old model: a later
// floor's shadow scales a composite that already saturated the RGBA16F target.
#include <acetate/effect.hpp>

class DropShadow final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.drop_shadow";
        e.display_name = "Harness control: drop shadow";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_EXPANDING;
        e.params = {{"opacity", "the shadow's alpha where the floor is opaque", 0.6f, 0.0f, 1.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "shadow",
                    .glsl = R"(
const ivec2 kOffset = ivec2(3, 4);  // right and down
// The floor's alpha at p, 0 off the canvas (clamping would smear the edge row into a band).
float coverage_at(ivec2 p) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(acetate_canvas.xy))))
        return 0.0;
    return texelFetch(previous, p, 0).a;
}
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 prev = texelFetch(previous, p, 0);
    float shadow = param_opacity * coverage_at(p - kOffset);
    // The clamp keeps prev.a <= a <= 1 whatever fp32 rounding does to the sum.
    float a = clamp(prev.a + (1.0 - prev.a) * shadow, prev.a, 1.0);
    out_color = vec4(prev.rgb, a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(DropShadow)
