// BREAKS rule 2a (coverage preserved), only beside another effect: it writes transparent black
// outside its floor's coverage bounds, "where there is nothing anyway". Alone on a floor that
// holds: the tile pass leaves nothing there. After an effect that spreads past the tiles (a
// glow, a shadow) it erases what that effect drew. Caught by `coverage` in
// contexts/after-spread only. Otherwise it is well_behaved's tint.
#include <acetate/effect.hpp>
#include <string>

namespace {

using namespace acetate::sdk;

class ClearsOutsideCoverage final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo e;
        e.id = "test.harness.clears_outside_coverage";
        e.display_name = "Harness battery: clears outside its coverage bounds";
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"gain", "multiplies the colour", 1.0f, 0.5f, 2.0f}};
        return e;
    }
    void build(Graph& graph, const Floor& floor) const override {
        const auto b = floor.coverage_bounds();
        graph.pass({.name = "tint",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 scene = ivec2(floor(acetate_scene_position(gl_FragCoord.xy)));
    if (any(lessThan(scene, BOUNDS.xy)) || any(greaterThanEqual(scene, BOUNDS.zw))) {
        out_color = vec4(0.0);
        return;
    }
    vec4 prev = texelFetch(previous, p, 0);
    out_color = vec4(prev.rgb * param_gain, prev.a);
}
)",
                    .inputs = {"previous"},
                    .defines = "#define BOUNDS ivec4(" + std::to_string(b.x0) + ", " +
                               std::to_string(b.y0) + ", " + std::to_string(b.x1) + ", " +
                               std::to_string(b.y1) + ")\n"});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(ClearsOutsideCoverage)
