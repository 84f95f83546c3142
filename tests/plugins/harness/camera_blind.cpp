// BROKEN on purpose: blind to the camera (ABI 1.2). It lights the floor around each point light
// by the distance from gl_FragCoord, which is a render pixel: without a camera that is the
// scene pixel, so every single image keeps the contract and looks right; through a camera the
// light pool moves with the view instead of staying on the floor. The fix is one call:
// acetate_scene_position(gl_FragCoord.xy).
// Caught by: CAMERA-REGION in relations/camera-region only.
#include <acetate/effect.hpp>

class CameraBlind final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.camera_blind";
        e.display_name = "Harness: takes render pixels for scene pixels";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "pool",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec2 pos = gl_FragCoord.xy;  // the mistake: a render pixel, not a scene position
    float light = 0.5;
    for (int i = 0; i < int(acetate_light_count); ++i) {
        AcetateLight l = acetate_lights[i];
        if (l.kind != ACETATE_LIGHT_POINT || !(l.radius > 0.0)) continue;
        float r = min(length(pos - l.position) / l.radius, 1.0);
        light += 0.5 * (1.0 - r * r);
    }
    out_color = vec4(prev.rgb * min(light, 1.0), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(CameraBlind)
