// BROKEN on purpose: every declared parameter must change the output. `radius` is declared
// (0..10, default 2) but neither build() nor any shader uses it; `strength` is connected
// (out.rgb = prev.rgb * (1 - 0.5 * strength), alpha kept). Caught by: the
// DISCONNECTED-PARAMETERS check only.
#include <acetate/effect.hpp>

class DisconnectedParam final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.disconnected_param";
        e.display_name = "Harness: disconnected parameter";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {
            {"strength", "darkens the colour", 0.5f, 0.0f, 1.0f},
            {"radius", "declared, never used", 2.0f, 0.0f, 10.0f},
        };
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "darken",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * (1.0 - 0.5 * param_strength), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(DisconnectedParam)
