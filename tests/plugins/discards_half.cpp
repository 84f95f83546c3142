// Breaks contract §6 on purpose: its only pass writes "result" but discards every odd column,
// so those pixels keep whatever "result" held. The poison tests (checked_memory_test.cpp) show
// that with CompositorOptions::poison they read as the poison.
#include <acetate/effect.hpp>

class DiscardsHalf final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.discards_half";
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "copy_even_columns",
                    .glsl = R"(
void main() {
    if ((int(gl_FragCoord.x) & 1) == 1) discard;
    out_color = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(DiscardsHalf)
