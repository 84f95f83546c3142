// A control for camera-scale: scale_blind with the fix. It darkens the floor by how much of it
// is transparent 4 scene pixels around, reading `previous` 4 * acetate_view_scale texels away
// (filtered, so a fraction of a texel reads between two). It passes camera-scale at a
// scale_tolerance of 0 (seed 1); it declares 0.05 so that scale_blind, declaring the same, shows
// that a declared tolerance does not hide a length in texels (that one needs 0.25).
// Caught by: nothing.
#include <acetate/effect.hpp>

class ScaleAware final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.scale_aware";
        e.display_name = "Harness: measures a length in scene pixels";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.scale_tolerance = 0.05f;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "edges",
                    .glsl = R"(
void main() {
    vec2 size = vec2(textureSize(previous, 0));
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float around = 0.0;
    for (int i = 0; i < 8; ++i) {
        vec2 d = round(4.0 * vec2(cos(0.785398 * float(i)), sin(0.785398 * float(i))));
        vec2 at = clamp(gl_FragCoord.xy + d * acetate_view_scale, vec2(0.5), size - 0.5);
        around += texture(previous, at / size).a;
    }
    out_color = vec4(prev.rgb * (0.5 + 0.0625 * around), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(ScaleAware)
