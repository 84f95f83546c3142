// BROKEN on purpose: floor names outside ASCII. build() tints a floor by its name's first letter,
// ('a'..'z' to 0..1) as (name[0] - 'a') / 25, assuming lowercase ASCII names; a name in UTF-8
// beyond ASCII ("étage", first byte 0xC3, a negative char) gives a tint far below 0, and colour
// scaled by 0.5 + 0.5 * tint goes negative. Otherwise (every "floor<N>", 300 'f's) colour is
// scaled by 0.5 to 1 and alpha is kept.
// Caught by: NON-NEGATIVE in floors/unicode-names only, and in a combined/* point drawn with it.
#include <acetate/effect.hpp>
#include <algorithm>
#include <string_view>

class AsciiFloorNames final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.ascii_floor_names";
        e.display_name = "Harness: tints by the floor name's first letter";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor& floor) const override {
        const std::string_view name = floor.name();
        const char first = name.empty() ? 'a' : name[0];
        const float data[] = {std::min(1.0f, float(first - 'a') / 25.0f)};
        graph.floor_data(data);
        graph.pass({.name = "tint",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * (0.5 + 0.5 * floor_data[0]), prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(AsciiFloorNames)
