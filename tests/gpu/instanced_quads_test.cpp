// Instanced-quad passes and CPU-prepared textures (test.sparks): quads land where floor_data
// says, take their colour from the texture, may draw past the floor's tiles (the floor is
// coverage-expanding, so it is composited by alpha instead of its stencil), and only their
// pixels are shaded.

#include <Imath/half.h>

#include "render_fixture.hpp"

namespace acetate::test {
namespace {

using InstancedQuads = RenderTest;

TEST_F(InstancedQuads, SparksLandWhereFloorDataSaysInThePaletteColour) {
    SceneDesc scene = make_scene(80, 40, {0, 0, 0, 0});
    const uint32_t floor = add_floor(scene, "ground");
    add_tile(scene, floor, solid(40, 40, {0.2f, 0.2f, 0.2f, 1}), {0, 0, 40, 40});  // left half
    scene.floors[floor].lights = {{{20, 20}, 1, {1, 0, 0}, 1}, {{60, 20}, 1, {0, 0.5f, 1}, 1}};
    EffectRef ref;
    ref.plugin = "test.sparks";
    ref.where = "floors[0].effects[0]";
    scene.floors[floor].effects = {ref};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    const ImageRGBA out = render(*compositor, floor, &stats);
    // Spark 0 over the tile, spark 1 past the tile's right edge (where the floor has no tiles).
    const float* over_tile = out.at(20, 20);
    EXPECT_EQ(over_tile[0], 1.0f);
    EXPECT_EQ(over_tile[2], 0.0f);
    const float* past_edge = out.at(60, 20);
    EXPECT_EQ(past_edge[1], 0.5f);
    EXPECT_EQ(past_edge[2], 1.0f);
    EXPECT_EQ(past_edge[3], 1.0f) << "coverage expanded past the tiles";
    // Outside the discs: the tile, or nothing at all.
    EXPECT_EQ(out.at(5, 5)[0], float(Imath::half(0.2f))) << "the tile, to half precision";
    EXPECT_EQ(out.at(75, 5)[3], 0.0f);
    EXPECT_EQ(out.at(60, 14)[3], 0.0f) << "quad corner outside the disc stays transparent";
    for (size_t i = 0; i < out.pixels.size(); i += 4)
        if (out.pixels[i + 3] == 0.0f) {
            ASSERT_TRUE(out.pixels[i] == 0 && out.pixels[i + 1] == 0 && out.pixels[i + 2] == 0);
        }
    EXPECT_EQ(stats.violations, 0u);
    // The sparks pass shades its two 10x10 quads, not the canvas.
    const FloorFrameReport& report = stats.floors.at(0);
    EXPECT_EQ(report.path, "through-target");
    // tile draw 40*40 + copy (whole canvas: expanding) + sparks 2*100 + composite (canvas)
    EXPECT_EQ(report.pixels_shaded, 40u * 40 + 80u * 40 + 200 + 80u * 40);
}

TEST_F(InstancedQuads, RectsBeyondFloorDataAreRefused) {
    SceneDesc scene = make_scene(16, 16);
    const uint32_t floor = add_floor(scene, "ground");
    add_tile(scene, floor, solid(16, 16, {0.2f, 0.2f, 0.2f, 1}), {0, 0, 16, 16});
    EffectRef ref;
    ref.plugin = "test.sparks";
    ref.where = "floors[0].effects[0]";
    scene.floors[floor].effects = {ref};  // no lights: the plugin refuses to build
    auto refused = Compositor::load(renderer(), scene, {});
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("needs at least one light"), std::string::npos)
        << refused.error().message;
}

}  // namespace
}  // namespace acetate::test

#include <cstdlib>
#include <fstream>

#include "plugins/plugin_loader.hpp"
#include "render/effect_pipelines.hpp"
#include "vulkan/shader_compiler.hpp"

namespace acetate::test {
namespace {

TEST_F(RenderTest, APassGivenAsSpirvRunsLikeItsGlsl) {
    // Compile the plugin's pass the way a plugin author would ship it: the host's declarations
    // for this effect with the uniform block effect.h documents for SPIR-V, then the body.
    auto plugin = renderer().plugins().load("test.spirv_pass");
    ASSERT_TRUE(plugin.ok()) << plugin.error().message;
    const std::string body =
        "void main() { vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);\n"
        "              out_color = vec4(c.rgb * param_gain, c.a); }\n";
    auto spirv = compile_glsl(
        "gain", ShaderStage::Fragment,
        effect_glsl_preamble(plugin.value()->descriptor, {"previous"}, ACETATE_PASS_FULLSCREEN,
                             false, FrameBlockDeclaration::Uniform) +
            body);
    ASSERT_TRUE(spirv.ok()) << spirv.error().message;
    const auto file = dir() / "gain.spv";
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(spirv->data()), std::streamsize(spirv->size() * 4));
    setenv("ACETATE_TEST_SPIRV_FILE", file.c_str(), 1);

    SceneDesc scene = make_scene(8, 8, {0, 0, 0, 0});
    const uint32_t floor = add_floor(scene, "ground");
    add_tile(scene, floor, solid(8, 8, {0.5f, 0.25f, 1.0f, 1}), {0, 0, 8, 8});
    EffectRef ref;
    ref.plugin = "test.spirv_pass";
    ref.params = {{"gain", 0.5}};
    ref.where = "floors[0].effects[0]";
    scene.floors[floor].effects = {ref};
    auto compositor = load(scene);
    unsetenv("ACETATE_TEST_SPIRV_FILE");
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, floor);
    EXPECT_EQ(out.at(3, 3)[0], 0.25f);
    EXPECT_EQ(out.at(3, 3)[1], 0.125f);
    EXPECT_EQ(out.at(3, 3)[2], 0.5f);
    EXPECT_EQ(out.at(3, 3)[3], 1.0f);
}

}  // namespace
}  // namespace acetate::test
