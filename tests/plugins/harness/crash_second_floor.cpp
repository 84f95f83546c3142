// BROKEN on purpose: the plugin must not bring down its host. build() raises SIGSEGV when it is
// built for floor 1 (a scene with one floor loads fine); its shader is a clean pass-through
// (colour * gain, alpha kept). Caught by: the harness's child process dying -> CRASH (only on
// scenes with two or more floors).
#include <acetate/effect.hpp>
#include <csignal>

class CrashSecondFloor final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.crash_second_floor";
        e.display_name = "Harness: crashes on floor 1";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"gain", "multiplies the colour", 1.0f, 0.0f, 2.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        if (floor.index() == 1) std::raise(SIGSEGV);
        graph.pass({.name = "pass_through",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * param_gain, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(CrashSecondFloor)
