// test.reload, built twice (tests/plugins/CMakeLists.txt): reload_v1 (RELOAD_VERSION 1) scales
// colour by 1/2, reload_v2 (RELOAD_VERSION 2) by 1/4, alpha kept. Two builds of one plugin id,
// for Host::reload_plugins (tests/gpu/plugin_reload_test.cpp).
#include <acetate/effect.hpp>

#if RELOAD_VERSION == 1
#define RELOAD_SCALE "0.5"
#elif RELOAD_VERSION == 2
#define RELOAD_SCALE "0.25"
#else
#error "RELOAD_VERSION must be 1 or 2"
#endif

class Reload final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.reload";
        e.version_major = RELOAD_VERSION;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "scale",
                    .glsl = "void main() {\n"
                            "    vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);\n"
                            "    out_color = vec4(c.rgb * " RELOAD_SCALE ", c.a);\n"
                            "}\n",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(Reload)
