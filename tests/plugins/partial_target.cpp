// Writes its intermediate target only in part, then shows the target as "result": floor 0
// writes the left two thirds, every other floor the middle third only, and nobody the right
// third. With CompositorOptions::poison the right third reads as the poison, while the left
// third on floor 1 shows what floor 0 wrote (targets are shared and never cleared between
// floors). Breaks contract §6 on purpose (checked_memory_test.cpp).
#include <acetate/effect.hpp>

class PartialTarget final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.partial_target";
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.target("scratch", 1);
        graph.pass({.name = "mark",
                    .glsl = R"(
void main() {
    float third = gl_FragCoord.x * acetate_output.z * 3.0;  // 0..3 across the target
    if (third >= 2.0 || (acetate_floor != 0 && third < 1.0)) discard;
    out_color = vec4(0.25 * float(acetate_floor + 1), 0.0, 0.0, 1.0);
}
)",
                    .output = "scratch"});
        graph.pass(
            {.name = "show",
             .glsl =
                 "void main() { out_color = texelFetch(scratch, ivec2(gl_FragCoord.xy), 0); }\n",
             .inputs = {"scratch"}});
    }
};
ACETATE_REGISTER_EFFECT(PartialTarget)
