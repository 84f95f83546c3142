// test.reload, version 1: scales colour by 1/2, alpha kept. reload_v1 and reload_v2 are two
// builds of one plugin id, for Host::reload_plugins (tests/gpu/plugin_reload_test.cpp).
#include <acetate/effect.hpp>

class Reload final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.reload";
        e.version_major = 1;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "scale",
                    .glsl = "void main() {\n"
                            "    vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);\n"
                            "    out_color = vec4(c.rgb * 0.5, c.a);\n"
                            "}\n",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(Reload)
