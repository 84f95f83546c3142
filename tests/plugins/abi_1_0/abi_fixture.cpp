// An effect that uses every feature of ABI 1.0, for the compatibility test
// (tests/gpu/abi_compat_test.cpp). It is built twice from this one source: against the committed
// copy of the 1.0 headers (tests/abi_1_0/include) and against the current SDK. Both builds must
// load in today's host and render bit-identically to the images the 1.0 host rendered
// (tests/abi_1_0/golden/). Do not change this file: the golden images were made from it.
//
// Features used: float, int and bool parameters with a preset; a declared mask kind read as an
// input; the floor's lights packed into floor_data; a half-size target; a CPU texture; an
// instanced-quad pass blended ADD; acetate_time, acetate_floor and acetate_output.
#include <acetate/effect.hpp>
#include <vector>

namespace {

using namespace acetate::sdk;

class AbiFixture final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "test.abi_fixture";
        e.display_name = "ABI 1.0 fixture";
        e.masks = {"water"};
        e.params = {
            {.name = "strength",
             .description = "Mix towards the blurred copy.",
             .default_value = 0.5f,
             .min_value = 0.0f,
             .max_value = 1.0f},
            {.name = "taps",
             .description = "Samples per axis.",
             .default_value = 2.0f,
             .min_value = 1.0f,
             .max_value = 4.0f,
             .type = ACETATE_PARAM_INT},
            {.name = "wave",
             .description = "Animate with time.",
             .default_value = 1.0f,
             .min_value = 0.0f,
             .max_value = 1.0f,
             .type = ACETATE_PARAM_BOOL},
        };
        e.presets = {{"low", {{"taps", 1.0f}}}, {"ultra", {{"taps", 4.0f}, {"strength", 0.8f}}}};
        return e;
    }

    void build(Graph& graph, const Floor& floor) const override {
        // floor_data: one rect per light (x, y, w, h), then the light colours (r, g, b, 0).
        std::vector<float> data;
        for (const AcetateLight& l : floor.lights())
            data.insert(data.end(),
                        {l.pos[0] - l.radius, l.pos[1] - l.radius, 2 * l.radius, 2 * l.radius});
        for (const AcetateLight& l : floor.lights())
            data.insert(data.end(), {l.color[0] * l.intensity, l.color[1] * l.intensity,
                                     l.color[2] * l.intensity, 0.0f});
        if (data.empty()) data.push_back(0.0f);
        graph.floor_data(data);
        const float ramp[] = {0.2f, 0.1f, 0.0f, 0.2f, 0.0f, 0.3f, 0.6f, 0.6f};
        graph.texture("ramp", 2, 1, ramp);
        graph.target("halved", 2);
        graph.pass({.name = "down",
                    .glsl = R"(
void main() {
    vec2 uv = gl_FragCoord.xy * acetate_output.zw;
    vec4 sum = vec4(0.0);
    int taps = int(param_taps);
    for (int i = 0; i < taps; ++i)
        for (int j = 0; j < taps; ++j)
            sum += texture(previous, uv + (vec2(i, j) - 0.5 * float(taps - 1)) * acetate_canvas.zw);
    out_color = sum / float(taps * taps);
}
)",
                    .inputs = {"previous"},
                    .output = "halved"});
        graph.pass({.name = "mix",
                    .glsl = R"(
void main() {
    vec2 uv = gl_FragCoord.xy * acetate_canvas.zw;
    vec4 base = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec4 blurred = texture(halved, uv);
    float water = texture(mask_water, uv).a;
    float wave = param_wave > 0.5 ? 0.5 + 0.5 * sin(acetate_time * 3.0 + uv.x * 20.0) : 1.0;
    vec4 tint = texture(texture_ramp, vec2(water, 0.5)) * float(acetate_floor + 1);
    vec3 rgb = mix(base.rgb, blurred.rgb * base.a / max(blurred.a, 1e-4), param_strength * wave);
    out_color = vec4(max(rgb + tint.rgb * tint.a * water * base.a, vec3(0.0)), base.a);
}
)",
                    .inputs = {"previous", "halved", "mask.water", "texture.ramp"}});
        const uint32_t lights = uint32_t(floor.lights().size());
        if (lights == 0) return;
        graph.pass({.name = "glints",
                    .glsl = R"(
void main() {
    vec4 base = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    int at = int(floor_data.length()) / 2 + 4 * acetate_instance;
    vec3 colour = vec3(floor_data[at], floor_data[at + 1], floor_data[at + 2]);
    float disc = max(0.0, 1.0 - 2.0 * length(acetate_uv - 0.5));
    out_color = vec4(colour * disc * disc * disc * base.a, 0.0);  // added; alpha unchanged
}
)",
                    .inputs = {"previous"},
                    .blend = ACETATE_BLEND_ADD,
                    .instance_count = lights,
                    .instance_data_offset = 0});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(AbiFixture)
