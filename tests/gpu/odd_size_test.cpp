// Odd sizes: 1x1, 1921x1079, a canvas at the device's maximum image dimension, and a clear
// error above it.

#include "render_fixture.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::test {
namespace {

using OddSize = RenderTest;

TEST_F(OddSize, OneByOne) {
    SceneDesc scene = make_scene(1, 1, {0, 0, 1, 1});
    const uint32_t floor = add_floor(scene, "only");
    add_tile(scene, floor, solid(1, 1, {0.5f, 0.0f, 0.0f, 0.5f}), {0, 0, 1, 1});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, floor);
    ASSERT_EQ(out.width, 1u);
    EXPECT_FLOAT_EQ(out.at(0, 0)[0], 0.5f);
    EXPECT_FLOAT_EQ(out.at(0, 0)[2], 0.5f);
    EXPECT_FLOAT_EQ(out.at(0, 0)[3], 1.0f);
}

TEST_F(OddSize, OddCanvasPutsEveryTileWhereItsRectSays) {
    SceneDesc scene = make_scene(1921, 1079, {0, 0, 0, 0});
    const uint32_t floor = add_floor(scene, "floor");
    add_tile(scene, floor, solid(3, 5, {0.25f, 0.5f, 0.75f, 1}), {1918, 1074, 3, 5});  // corner
    add_tile(scene, floor, solid(7, 3, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 7, 3});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, floor);
    ASSERT_EQ(out.width, 1921u);
    ASSERT_EQ(out.height, 1079u);
    EXPECT_EQ(out.at(1920, 1078)[2], 0.75f);
    EXPECT_EQ(out.at(1918, 1074)[2], 0.75f);
    EXPECT_EQ(out.at(1917, 1074)[3], 0.0f);
    EXPECT_EQ(out.at(1918, 1073)[3], 0.0f);
    EXPECT_EQ(out.at(6, 2)[0], 0.5f);
    EXPECT_EQ(out.at(7, 2)[3], 0.0f);
    EXPECT_EQ(out.at(960, 540)[3], 0.0f);
}

TEST_F(OddSize, CanvasAtTheDeviceMaximumRendersAndAboveItFailsClearly) {
    const uint32_t max_dim = context().properties().limits.maxImageDimension2D;
    SceneDesc scene = make_scene(max_dim, 2, {0, 0, 0, 1});
    const uint32_t floor = add_floor(scene, "floor");
    add_tile(scene, floor, solid(4, 2, {1, 0.5f, 0.25f, 1}), {double(max_dim - 4), 0, 4, 2});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, floor);
    ASSERT_EQ(out.width, max_dim);
    EXPECT_EQ(out.at(max_dim - 1, 1)[0], 1.0f);
    EXPECT_EQ(out.at(max_dim - 5, 1)[0], 0.0f);

    scene.width = max_dim + 1;
    auto refused = Compositor::load(renderer(), scene, {});
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::DeviceLimit);
    EXPECT_NE(refused.error().message.find("canvas"), std::string::npos) << refused.error().message;
    EXPECT_NE(refused.error().message.find(std::to_string(max_dim)), std::string::npos);
    EXPECT_EQ(refused.error().message.find('\n'), std::string::npos) << "one line";
}

}  // namespace
}  // namespace acetate::test
