// BROKEN on purpose: rule 4, "no NaN or Inf, ever". It writes one NaN: the red channel of the
// canvas-centre pixel, ivec2(canvas * 0.5), when that pixel is covered (a > 0); alpha is kept.
// Everywhere else it is colour * gain. Caught by: the FINITE check only.
#include <acetate/effect.hpp>

class NanPixel final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.nan_pixel";
        e.display_name = "Harness: one NaN pixel";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"gain", "multiplies the colour", 1.0f, 0.0f, 2.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "poison",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 prev = texelFetch(previous, p, 0);
    vec4 o = vec4(prev.rgb * param_gain, prev.a);
    if (p == ivec2(acetate_canvas.xy * 0.5) && prev.a > 0.0)
        o.r = uintBitsToFloat(0x7fc00000u);  // a quiet NaN
    out_color = o;
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(NanPixel)
