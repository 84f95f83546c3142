// A pass that reads a target no earlier pass writes: the host refuses the declaration.
#include <acetate/effect.hpp>

class ReadsUnwritten final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.reads_unwritten";
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.target("blurred", 2);
        graph.pass(
            {.name = "combine",
             .glsl =
                 "void main() { out_color = texelFetch(previous, ivec2(gl_FragCoord.xy), 0); }\n",
             .inputs = {"previous", "blurred"}});
    }
};
ACETATE_REGISTER_EFFECT(ReadsUnwritten)
