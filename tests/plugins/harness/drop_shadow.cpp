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
        // At scale 1/2 the shadow is laid over coverage averaged over 2x2 scene pixels, and
        // "over" of averages is not the average of "over"s: camera-scale measured 0.179 of the
        // largest alpha nearby (strictness 1, seed 1).
        e.scale_tolerance = 0.25f;
        e.params = {{"opacity", "the shadow's alpha where the floor is opaque", 0.6f, 0.0f, 1.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "shadow",
                    .glsl = R"(
const vec2 kOffset = vec2(3, 4);  // right and down, scene pixels
// The floor's alpha at texel p, 0 off the output (clamping would smear the edge row into a band).
float texel_alpha(ivec2 p) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(acetate_canvas.xy))))
        return 0.0;
    return texelFetch(previous, p, 0).a;
}
// Bilinear by hand at render position q: at a texel's centre exactly that texel, whatever the
// output's size (a sampler's normalised coordinate would not be).
float coverage_at(vec2 q) {
    vec2 at = q - 0.5, f = at - floor(at);
    ivec2 p = ivec2(floor(at));
    return mix(mix(texel_alpha(p), texel_alpha(p + ivec2(1, 0)), f.x),
               mix(texel_alpha(p + ivec2(0, 1)), texel_alpha(p + ivec2(1, 1)), f.x), f.y);
}
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float shadow = param_opacity * coverage_at(gl_FragCoord.xy - kOffset * acetate_view_scale);
    // The clamp keeps prev.a <= a <= 1 whatever fp32 rounding does to the sum.
    float a = clamp(prev.a + (1.0 - prev.a) * shadow, prev.a, 1.0);
    out_color = vec4(prev.rgb, a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(DropShadow)
