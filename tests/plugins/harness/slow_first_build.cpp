// CORRECT, but slowed once: stands for a case that a loaded machine starved, not a plugin that
// hangs. It takes a numbered ticket in $ACETATE_TEST_FLAKY_DIR at every build() (as `flaky`
// does), and the build that takes ticket 1 computes for 30 s of CPU time before going on; every
// other build, and every build without that folder, is quick. The effect itself darkens the
// colour and keeps alpha.
// Must pass: a TIMEOUT is run once more in a fresh process before it counts, and that run
// (ticket 2) finishes (tests/harness/harness_flaky_test.cpp).
#include <acetate/effect.hpp>
#include <ctime>

#include "ticket.hpp"

namespace {

void compute_for(double cpu_seconds) {
    volatile double sink = 0;
    for (timespec t{}; clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) == 0 &&
                       double(t.tv_sec) + double(t.tv_nsec) * 1e-9 < cpu_seconds;)
        for (int i = 0; i < 100000; ++i) sink = sink + 1.0;
}

}  // namespace

class SlowFirstBuild final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.slow_first_build";
        e.display_name = "Harness: slow first build";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        if (take_ticket() == 1) compute_for(30.0);
        graph.pass({.name = "darken",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * 0.9, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(SlowFirstBuild)
