// BROKEN on purpose: a mask at 1 everywhere. A wet look darkens the floor by the water mask's
// optical depth, -log(1 - m), compressed as depth / (1 + depth); where the mask is exactly 1 the
// depth is infinite and that is Inf / Inf = NaN. The mask is read through a 3x3 tent blur (four
// bilinear taps at texel corners), so a varying mask never averages to exactly 1: only a mask
// that is 1 over a whole 3x3 block does. Otherwise colour is scaled by 0.7 to 1 and alpha is
// kept. Caught by: FINITE in masks/full and masks/above-one (above 1 the logarithm's argument is
// negative), and in a combined/* point drawn with masks full, above 1, or in one-pixel lines
// (where lines meet at the tile's corner, a small canvas has a whole 3x3 block at 1).
#include <acetate/effect.hpp>

class FullMask final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.full_mask";
        e.display_name = "Harness: infinite optical depth under a full mask";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.masks = {"water"};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "wet",
                    .glsl = R"(
float water(vec2 corner) {
    return texture(mask_water, corner * acetate_canvas.zw).r;
}
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 p = gl_FragCoord.xy;
    float h = 0.5 * acetate_view_scale;  // half a scene pixel
    float m = 0.25 * (water(p + vec2(-h, -h)) + water(p + vec2(h, -h)) + water(p + vec2(-h, h)) +
                      water(p + vec2(h, h)));
    float depth = -log(1.0 - m);  // infinite where the water is full
    float wet = depth / (1.0 + depth);
    out_color = vec4(prev.rgb * (1.0 - 0.3 * wet), prev.a);
}
)",
                    .inputs = {"previous", "mask.water"}});
    }
};
ACETATE_REGISTER_EFFECT(FullMask)
