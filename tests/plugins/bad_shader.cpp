// A pass whose GLSL does not compile.
#include <acetate/effect.hpp>

class BadShader final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.bad_shader";
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "broken",
                    .glsl = "void main() { out_color = undeclared_thing; }\n",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(BadShader)
