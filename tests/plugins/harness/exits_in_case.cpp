// BROKEN on purpose: the plugin must not end its host's process. build() prints why it gives up
// and calls std::exit(7) when it is built for floor 1 (a scene with one floor loads fine); its
// shader is a clean pass-through (colour * gain, alpha kept). Caught by: the harness's child
// process exiting with a status the harness never uses -> CRASH, "the plugin exited with status
// 7 during the case" followed by the printed line (only on scenes with two or more floors that
// put the plugin on floor 1).
#include <acetate/effect.hpp>
#include <cstdio>
#include <cstdlib>

class ExitsInCase final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.exits_in_case";
        e.display_name = "Harness: exits on floor 1";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"gain", "multiplies the colour", 1.0f, 0.0f, 2.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        if (floor.index() == 1) {
            std::fprintf(stderr, "exits_in_case: floor 1 is not supported, giving up\n");
            std::exit(7);
        }
        graph.pass({.name = "pass_through",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * param_gain, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(ExitsInCase)
