// BROKEN on purpose: rule 6, "isolation: an effect sees only its own floor". The target
// `trail` is shared by this plugin's instances on every floor and never cleared by the host,
// and this effect never replaces it whole: each floor only stamps its own 4x4 square into it
// (scene rect (4 + 6 * floor, 2, 4, 4)), so the squares of floors rendered earlier stay, and
// "apply" brightens the floor under every square in `trail`, its own or another floor's.
// Rendering floors 0, 1, 0 gives a different floor 0 the second time. Alpha is kept, colour
// only scaled by a positive factor, the output is finite and repeatable for a given order of
// floors, and `gain` is connected. Caught by: the STATE-ISOLATION check, and DETERMINISM in
// determinism/after-history (its earlier frames leave floor 1's stamps for floor 0).
//
// The host refuses an instanced pass as the first writer of an output, so "init" is a
// fullscreen REPLACE pass into `trail` that discards every fragment: it satisfies the
// load-time check and writes nothing. That is the bug, and it is deliberate.
//
// The host does not clear a target when it allocates it either, so a fresh `trail` holds
// whatever the memory held (seen on lavapipe: a different pattern in each process). A stamp is
// therefore an exact magic colour, and "apply" treats every other value as "no stamp". So the
// first render of a floor in a fresh process is repeatable (the determinism check passes) and
// only the stamps of floors rendered earlier leak in.
#include <acetate/effect.hpp>

class FloorStateLeak final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.floor_state_leak";
        e.display_name = "Harness: floor state leak";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        e.params = {{"gain", "how much the stamped squares brighten", 0.5f, 0.0f, 1.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        graph.target("trail", 1);
        const float rect[] = {4.0f + 6.0f * float(floor.index()), 2.0f, 4.0f, 4.0f};
        graph.floor_data(rect);
        graph.pass({.name = "init",
                    .glsl = "void main() { discard; }  // should clear `trail`; clears nothing\n",
                    .output = "trail"});
        graph.pass({.name = "stamp",
                    .glsl = "void main() { out_color = vec4(0.3125, 0.6875, 0.1875, 0.5625); }\n",
                    .output = "trail",
                    .blend = ACETATE_BLEND_REPLACE,
                    .instance_count = 1,
                    .instance_data_offset = 0});
        graph.pass({.name = "apply",
                    .glsl = R"(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 prev = texelFetch(previous, p, 0);
    // Only the exact stamp colour (exact in RGBA16F and RGBA32F) counts; anything else, such as
    // the uninitialised memory of a fresh target or a NaN, is no stamp.
    bool stamped = all(equal(texelFetch(trail, p, 0), vec4(0.3125, 0.6875, 0.1875, 0.5625)));
    out_color = vec4(prev.rgb * (1.0 + (stamped ? param_gain : 0.0)), prev.a);
}
)",
                    .inputs = {"previous", "trail"}});
    }
};
ACETATE_REGISTER_EFFECT(FloorStateLeak)
