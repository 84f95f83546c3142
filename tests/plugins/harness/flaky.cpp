// BROKEN on purpose: its verdict depends on what ran before it. Like a plugin that keeps a cache
// on disk and gets the first run wrong, it takes a numbered ticket in the folder
// $ACETATE_TEST_FLAKY_DIR at every build() (creating ticket-1, ticket-2, ... exclusively, so
// concurrent processes never share one), and the build that takes ticket 1 raises alpha by
// 0.25 everywhere (a coverage-preserving effect changing coverage). Every other build is
// correct, and so is every build without that folder.
// Caught by: `validate --repeat N` (N >= 2) as FLAKY: exactly one run fails (the COVERAGE
// check), the same case's other runs pass. A single run reads an ordinary FAIL.
#include <acetate/effect.hpp>

#include "ticket.hpp"

class Flaky final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.flaky";
        e.display_name = "Harness: flaky";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        const float data[] = {take_ticket() == 1 ? 0.25f : 0.0f};
        graph.floor_data(data);
        graph.pass({.name = "tint",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * 0.9, prev.a + floor_data[0]);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(Flaky)
