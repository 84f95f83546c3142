// BROKEN on purpose: blind to the render scale (ABI 1.2). It darkens the floor by how much of
// it is transparent 4 pixels around, reading `previous` 4 texels away: without a camera, and
// through one at scale 1, a texel is a scene pixel, so every such image keeps the contract and
// looks right; at scale 1/2 a texel is two scene pixels and the darkening reaches twice as far.
// It declares the same scale_tolerance as its control, scale_aware (0.05, which the control does
// not need), whose only difference is the fix: offsets of 4 * acetate_view_scale texels.
// Caught by: CAMERA-SCALE in relations/camera-scale only.
#include <acetate/effect.hpp>

class ScaleBlind final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.scale_blind";
        e.display_name = "Harness: measures a length in texels";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.scale_tolerance = 0.05f;  // what scale_aware declares: the bug still fails beyond it
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "edges",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy), last = textureSize(previous, 0) - 1;
    vec4 prev = texelFetch(previous, p, 0);
    float around = 0.0;
    for (int i = 0; i < 8; ++i) {
        ivec2 d = ivec2(round(4.0 * vec2(cos(0.785398 * float(i)), sin(0.785398 * float(i)))));
        around += texelFetch(previous, clamp(p + d, ivec2(0), last), 0).a;  // the mistake
    }
    out_color = vec4(prev.rgb * (0.5 + 0.0625 * around), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(ScaleBlind)
