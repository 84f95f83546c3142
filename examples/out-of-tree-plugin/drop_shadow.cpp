// com.example.drop_shadow: a floor effect that casts its floor's shadow, offset and blurred, and
// draws the floor over it. Coverage-expanding: the shadow falls where no tile is.
// Built against the installed Acetate SDK; see README.md.
#include <acetate/effect.hpp>
#include <cmath>

#include "drop_shadow_shaders.hpp"  // generated from the two .frag files by acetate_add_effect()

namespace {

using namespace acetate::sdk;

inline constexpr ColorParam kColour{"colour", "Shadow colour, linear RGB.", {0.0f, 0.0f, 0.0f}};
inline constexpr FloatParam kOpacity{"opacity", "Shadow alpha under an opaque tile.", 0.6f, 0.0f,
                                     1.0f};
// x right, y down; a vector parameter is a JSON array in a scene, a vec2 in GLSL.
inline constexpr Vec2Param kOffset{
    "offset", "Shadow offset, scene pixels.", {6.0f, 8.0f}, -32.0f, 32.0f};
inline constexpr FloatParam kRadius{"radius", "Blur radius, scene pixels.", 6.0f, 0.0f, 32.0f};
// A cost knob, not a look: hidden (the last field), so only the presets set it.
inline constexpr IntParam kTaps{"taps", "Blur samples per side, at most.", 8, 1, 16, true};

class DropShadow final : public Effect {
  public:
    EffectInfo info() const override {
        EffectInfo info;
        info.id = "com.example.drop_shadow";
        info.display_name = "Drop shadow (example)";
        info.scope = ACETATE_SCOPE_FLOOR;
        info.coverage = ACETATE_COVERAGE_EXPANDING;
        info.params = {kColour, kOpacity, kOffset, kRadius, kTaps};
        info.presets = quality_presets({{kTaps, {4, 6, 8, 16}}});
        return info;
    }

    // previous -> blur_x -> across -> blur_y -> shadow; then previous over shadow -> result.
    void build(Graph& graph, const Floor& floor) const override {
        // The reach: the shadow lands |offset| away and spreads `radius` further. Each bilinear
        // read of a half-size target reaches up to one of its texels (2 pixels) past the point
        // read; two such reads (blur_y, composite) add 4 pixels, and reading the floor 1 more.
        const auto [dx, dy] = floor[kOffset];
        graph.reach(uint32_t(std::ceil(std::hypot(dx, dy) + floor[kRadius])) + 5);

        // The blur runs at half size; one shader serves both directions.
        graph.target("across", 2);
        graph.target("shadow", 2);
        graph.pass({.name = "blur_x",
                    .glsl = drop_shadow_blur_frag,
                    .inputs = {"previous"},
                    .output = "across",
                    .defines = "#define DIRECTION vec2(1.0, 0.0)\n",
                    .input_names = {"src"}});
        graph.pass({.name = "blur_y",
                    .glsl = drop_shadow_blur_frag,
                    .inputs = {"across"},
                    .output = "shadow",
                    .defines = "#define DIRECTION vec2(0.0, 1.0)\n",
                    .input_names = {"src"}});
        graph.pass(
            {.name = "composite", .glsl = drop_shadow_frag, .inputs = {"previous", "shadow"}});
    }
};

}  // namespace

ACETATE_REGISTER_EFFECT(DropShadow)
