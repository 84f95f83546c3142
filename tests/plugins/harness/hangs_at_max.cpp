// BROKEN on purpose: the plugin must finish loading. build() spins forever (a loop on a
// volatile counter, which the compiler cannot remove) when `iterations` is at its maximum, 8;
// at any other value it builds a clean pass (colour * (1 + 0.05 * iterations), alpha kept).
// Caught by: the harness's time limit -> TIMEOUT (only the case with iterations = 8).
#include <acetate/effect.hpp>
#include <cstdint>

class HangsAtMax final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.hangs_at_max";
        e.display_name = "Harness: hangs at maximum iterations";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"iterations", "how many rounds of work", 2.0f, 1.0f, 8.0f, ACETATE_PARAM_INT}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        if (floor.param("iterations") >= 8.0f) {
            volatile uint64_t counter = 0;
            for (;;) counter = counter + 1;  // never returns
        }
        graph.pass({.name = "brighten",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * (1.0 + 0.05 * param_iterations), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(HangsAtMax)
