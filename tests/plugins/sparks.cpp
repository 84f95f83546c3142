// A well-behaved particle effect for the instanced-quad tests: copies the floor, then draws one
// hard-edged disc per spark, coloured from a palette texture prepared on the CPU.
// Coverage-expanding: sparks may fly past the floor's tiles.
#include <acetate/effect.hpp>
#include <vector>

class Sparks final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.sparks";
        e.coverage = ACETATE_COVERAGE_EXPANDING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        // Spark i: a 10x10 quad; the scene's lights give their centres (one spark per light).
        std::vector<float> rects;
        std::vector<float> palette;
        for (const AcetateLight& l : floor.lights()) {
            rects.insert(rects.end(), {l.pos[0] - 5, l.pos[1] - 5, 10, 10});
            palette.insert(palette.end(), {l.color[0], l.color[1], l.color[2], 1.0f});
        }
        if (rects.empty()) throw std::runtime_error("test.sparks needs at least one light");
        graph.floor_data(rects);
        graph.texture("palette", uint32_t(palette.size() / 4), 1, palette);
        graph.pass(
            {.name = "copy",
             .glsl =
                 "void main() { out_color = texelFetch(previous, ivec2(gl_FragCoord.xy), 0); }\n",
             .inputs = {"previous"}});
        graph.pass({.name = "sparks",
                    .glsl = R"(
void main() {
    vec4 colour = texelFetch(texture_palette, ivec2(acetate_instance, 0), 0);
    float inside = length(acetate_uv - 0.5) < 0.5 ? 1.0 : 0.0;
    out_color = colour * inside;  // premultiplied: a == 0 outside the disc, rgb too
}
)",
                    .inputs = {"texture.palette"},
                    .blend = ACETATE_BLEND_OVER,
                    .instance_count = uint32_t(rects.size() / 4)});
    }
};
ACETATE_REGISTER_EFFECT(Sparks)
