// BROKEN on purpose: a mask kind the floor does not have. build() hands the shader its
// shoreline settings (the mask's scale and the strength) only when the floor has the water
// mask; on a floor without it the shader divides the (transparent) mask by the host's default
// floor data, zeros: 0 / 0 = NaN over the whole floor. With the mask present, empty, full or
// above 1 (taken as 1), colour is scaled by 0.7 to 1 and alpha is kept. Caught by: FINITE in
// masks/absent only, and in a combined/* point drawn without masks.
#include <acetate/effect.hpp>

class AbsentMask final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.absent_mask";
        e.display_name = "Harness: no settings on floors without water";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.masks = {"water"};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        if (floor.has_mask("water")) {              // and otherwise? the shader still divides by it
            const float settings[] = {1.0f, 0.3f};  // mask scale, strength
            graph.floor_data(settings);
        }
        graph.pass({.name = "shore",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float m = texelFetch(mask_water, ivec2(gl_FragCoord.xy), 0).r;
    float wet = min(m, 1.0) / floor_data[0];  // 0 / 0 without the settings
    out_color = vec4(prev.rgb * (1.0 - floor_data[1] * wet), prev.a);
}
)",
                    .inputs = {"previous", "mask.water"}});
    }
};
ACETATE_REGISTER_EFFECT(AbsentMask)
