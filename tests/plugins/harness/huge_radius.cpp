// BROKEN on purpose: a light with a huge radius. Each light's disc gets a soft edge from the
// logistic curve, written naively as e / (1 + e) with e = exp((r - d) / 256): with r = 10^6 the
// exponent is in the thousands, e is infinite and the edge is Inf / Inf = NaN over the whole
// floor (even the light of radius 2 * 10^4 off the canvas stays below exp(88)). Otherwise colour
// is scaled by 0.8 to 1 and alpha is kept. Caught by: FINITE in lights/huge-radius only, and in a
// combined/* point drawn with huge lights.
#include <acetate/effect.hpp>
#include <vector>

class HugeRadius final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.huge_radius";
        e.display_name = "Harness: light edges overflowing with the radius";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        // [count, then per light x, y, radius, intensity]
        std::vector<float> data{float(floor.lights().size())};
        for (const AcetateLight& l : floor.lights())
            data.insert(data.end(), {l.pos[0], l.pos[1], l.radius, l.intensity});
        graph.floor_data(data);
        graph.pass({.name = "discs",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    float lit = 0.0;
    for (int i = 0; i < int(floor_data[0]); ++i) {
        vec2 d = acetate_scene_position(gl_FragCoord.xy) -
                 vec2(floor_data[1 + 4 * i], floor_data[2 + 4 * i]);
        float e = exp((floor_data[3 + 4 * i] - length(d)) / 256.0);  // overflows with r
        lit += floor_data[4 + 4 * i] * e / (1.0 + e);
    }
    out_color = vec4(prev.rgb * (0.8 + 0.2 * lit / (1.0 + lit)), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(HugeRadius)
