// Reports what ABI 1.1 gives a plugin, for tests/gpu/sdk11_features_test.cpp: each pixel of row 0
// holds some values the host passed (params, phases, clock, lights, mask sums computed at
// build, floor facts, an RG32F target read through a renamed input); every other pixel is the
// floor unchanged. Run it with RGBA32F floors so the values come back exactly.
#include <acetate/effect.hpp>
#include <vector>

namespace {

using namespace acetate::sdk;

inline constexpr ColorParam kTint{"tint", "A colour.", {0.25f, 0.5f, 0.75f}};
inline constexpr Vec2Param kOffset{"offset", "A vector.", {1.0f, -2.0f}, -8.0f, 8.0f};
inline constexpr IntParam kTaps{"taps", "A quality knob.", 2, 1, 8, /*hidden=*/true};

class Sdk11Probe final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "test.sdk11_probe";
        e.masks = {"water", "fire"};
        e.params = {kTint, kOffset, kTaps};
        e.presets = quality_presets({{kTaps, {1, 2, 4, 8}}});
        return e;
    }

    void build(Graph& graph, const Floor& floor) const override {
        // The water mask's alpha summed at build, with its weighted centroid, and the fire
        // mask's sum (the floor has none: an all-zero image, never null).
        const Mask water = floor.mask("water");
        double sum = 0, cx = 0, cy = 0;
        for (uint32_t y = 0; y < water.height; ++y)
            for (uint32_t x = 0; x < water.width; ++x) {
                const double a = water.data[(size_t(y) * water.width + x) * 4 + 3];
                sum += a, cx += a * (x + 0.5), cy += a * (y + 0.5);
            }
        const Mask fire = floor.mask("fire");
        double fire_sum = 0;
        for (float v : fire.data) fire_sum += v;
        const Bounds b = floor.coverage_bounds();
        const std::vector<float> data{
            float(sum),           float(cx / sum),     float(cy / sum),
            float(fire_sum),      float(b.x0),         float(b.y0),
            float(b.x1),          float(b.y1),         float(floor.floor_count()),
            float(floor.index()), float(floor[kTaps]), float(water.width * 10000 + water.height)};
        graph.floor_data(data);
        graph.phase("slow", 0.7);
        graph.target("field", 2, ACETATE_FORMAT_RG32F);
        // A value a half float cannot hold: the target must keep 32 bits.
        graph.pass({.name = "field",
                    .glsl = "void main() { out_color = vec4(gl_FragCoord.xy * 1000.123, 0, 0); }\n",
                    .output = "field"});
        graph.pass({.name = "report",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 base = texelFetch(previous, p, 0);
    vec3 v = base.rgb;
    if (p.y == 0) {
        if (p.x == 0) v = param_tint;
        if (p.x == 1) v = vec3(param_offset, float(TAPS));
        if (p.x == 2) v = vec3(phase_slow, acetate_time_fraction, acetate_time_whole);
        if (p.x == 3) v = vec3(float(acetate_light_count), acetate_lights[0].height,
                               acetate_lights[acetate_light_count - 1].direction.z);
        if (p.x == 4) v = vec3(floor_data[0], floor_data[1], floor_data[2]);
        if (p.x == 5) v = vec3(floor_data[3], floor_data[4], floor_data[5]);
        if (p.x == 6) v = vec3(floor_data[6], floor_data[7], floor_data[8]);
        if (p.x == 7) v = vec3(floor_data[9], floor_data[10], floor_data[11]);
        if (p.x == 8) v = vec3(acetate_size_src.xy, acetate_size_src.z);
        if (p.x == 9) v = vec3(texelFetch(src, ivec2(3, 2), 0).xy, 0.0);
        if (p.x == 10) v = acetate_lights[acetate_light_count - 1].direction;
        if (p.x == 11) v = vec3(float(acetate_lights[acetate_light_count - 1].kind),
                                acetate_lights[1].position);
    }
    out_color = vec4(v * base.a, base.a);
}
)",
                    .inputs = {"previous", "field"},
                    .defines = "#define TAPS " + std::to_string(floor[kTaps]) + "\n",
                    .input_names = {"", "src"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(Sdk11Probe)
