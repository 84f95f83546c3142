// BROKEN on purpose: rule 6, "`result` is not cleared for you: the first pass that writes it
// must write every pixel of its scissor". Its only pass discards where the floor is
// transparent (prev.a == 0), relying on `result` holding zeros there, as it happens to in a
// plain host; elsewhere it scales colour by 0.9 and keeps alpha. The harness fills `result`
// with a per-process poison before the effect runs, so those pixels keep the poison. Caught
// by: FINITE (the NaN poison), COVERAGE (the finite poisons, alpha 0.75 or 0.5 where the input
// had 0) and DETERMINISM (determinism/run-1 and run-2 differ by their poisons) in nearly every
// case with transparent pixels. State isolation renders in one process, with one poison, and
// passes.
#include <acetate/effect.hpp>

class ResultPartlyUnwritten final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.result_partly_unwritten";
        e.display_name = "Harness: leaves transparent pixels of result unwritten";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        graph.pass({.name = "dim",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    if (prev.a == 0.0) discard;  // "result is zero there anyway": it is not
    out_color = vec4(prev.rgb * 0.9, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(ResultPartlyUnwritten)
