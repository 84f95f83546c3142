// BROKEN on purpose: a light with a tiny radius. Each light is a Gaussian splat,
// exp(-d^2 / r^2), normalised so that the 5x5 pixels around its centre sum to its intensity
// (lights of any size carry the same energy); build() computes that sum. With r = 10^-4 pixels
// the Gaussian underflows to 0 at every pixel centre, the sum is 0, and the shader's
// weight / sum is 0 / 0 = NaN over the whole floor. Otherwise the floor gets up to 0.25 * a of
// light (alpha kept, colour stays 0 where a = 0). (The classic form of this bug, a peak
// intensity / r^2 overflowing an RGBA16F target, cannot be caught on lavapipe: it stores values
// beyond 65504 as 65504, not infinity.) Caught by: FINITE in lights/tiny-radius only, and in a
// combined/* point drawn with tiny lights.
#include <acetate/effect.hpp>
#include <cmath>
#include <vector>

class TinyRadius final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.tiny_radius";
        e.display_name = "Harness: splats normalised by an underflowing sum";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        // [count, then per light x, y, radius, intensity / sum, r, g, b, 0]
        std::vector<float> data{float(floor.lights().size())};
        for (const AcetateLight& l : floor.lights()) {
            float sum = 0.0f;
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) {
                    const float x = std::floor(l.pos[0]) + float(dx) + 0.5f - l.pos[0];
                    const float y = std::floor(l.pos[1]) + float(dy) + 0.5f - l.pos[1];
                    sum += std::exp(-(x * x + y * y) / (l.radius * l.radius));
                }
            data.insert(data.end(), {l.pos[0], l.pos[1], l.radius, l.intensity, sum, l.color[0],
                                     l.color[1], l.color[2]});
        }
        graph.floor_data(data);
        graph.pass({.name = "splats",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    vec3 light = vec3(0.0);
    for (int i = 0; i < int(floor_data[0]); ++i) {
        int at = 1 + 8 * i;
        vec2 d = acetate_scene_position(gl_FragCoord.xy) - vec2(floor_data[at], floor_data[at + 1]);
        float r = floor_data[at + 2];
        float weight = exp(-dot(d, d) / (r * r)) / floor_data[at + 4];  // 0 / 0 for tiny r
        light += floor_data[at + 3] * weight *
                 vec3(floor_data[at + 5], floor_data[at + 6], floor_data[at + 7]);
    }
    out_color = vec4(prev.rgb + prev.a * 0.25 * light / (1.0 + light), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(TinyRadius)
