// BROKEN on purpose: rule 5, "deterministic". build() draws a colour factor in [0.5, 1.5] from
// std::random_device and hands it to the shader as floor_data[0], so every load (and every
// process) renders different colours. Alpha is kept and the factor is positive, so the output
// is otherwise valid. Caught by: the DETERMINISM check only (renders differ between loads).
#include <acetate/effect.hpp>
#include <random>

class Nondeterministic final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.nondeterministic";
        e.display_name = "Harness: nondeterministic";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        std::random_device device;
        std::uniform_real_distribution<float> factor(0.5f, 1.5f);
        const float data[] = {factor(device)};
        graph.floor_data(data);
        graph.pass({.name = "scale",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * floor_data[0], prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(Nondeterministic)
