// Warm floor switch (docs/design.md, L-warm-switch): after load, switching the active floor loads,
// allocates and compiles nothing, and coming back gives the same image bit for bit.

#include <cstring>

#include "render_fixture.hpp"

namespace acetate::test {
namespace {

using WarmSwitch = RenderTest;

TEST_F(WarmSwitch, Floors010DoNoWorkAfterLoadAndFrame3EqualsFrame1) {
    SceneDesc scene = make_scene(64, 48, {0.05f, 0.05f, 0.06f, 1});
    for (uint32_t f = 0; f < 3; ++f) {
        const uint32_t floor = add_floor(scene, "floor" + std::to_string(f));
        add_tile(scene, floor, solid(32, 24, {0.1f * (f + 1), 0.2f, 0.3f, 0.5f + 0.2f * f}),
                 {8.0 * f, 6.0 * f, 32, 24});
    }
    for (OutputView view : {OutputView::Normal, OutputView::FloorAlpha}) {
        CompositorOptions options;
        options.view = view;
        auto compositor = load(scene, options);
        ASSERT_TRUE(compositor);
        const auto held_before = compositor->targets_held().size();
        std::vector<ImageRGBA> frames;
        for (uint32_t floor : {0u, 1u, 0u}) {
            FrameStats stats;
            frames.push_back(render(*compositor, floor, &stats));
            // Every frame, the first included: load created and warmed everything.
            EXPECT_EQ(stats.images_loaded, 0u) << "floor " << floor;
            EXPECT_EQ(stats.targets_allocated, 0u) << "floor " << floor;
            EXPECT_EQ(stats.shaders_compiled, 0u) << "floor " << floor;
            EXPECT_EQ(stats.pipelines_created, 0u) << "floor " << floor;
        }
        EXPECT_EQ(compositor->targets_held().size(), held_before);
        ASSERT_EQ(frames[0].pixels.size(), frames[2].pixels.size());
        EXPECT_EQ(std::memcmp(frames[0].pixels.data(), frames[2].pixels.data(),
                              frames[0].pixels.size() * sizeof(float)),
                  0)
            << "frame 3 differs from frame 1 (view " << to_string(view) << ")";
        EXPECT_GT(max_abs_difference(frames[0], frames[1]), 0.0) << "floors 0 and 1 should differ";
    }
}

TEST_F(WarmSwitch, WithFloorAndGlobalEffectsTooNothingIsDoneAfterLoad) {
    SceneDesc scene = make_scene(48, 32, {0, 0, 0, 1});
    for (uint32_t f = 0; f < 2; ++f) {
        const uint32_t floor = add_floor(scene, "floor" + std::to_string(f));
        add_tile(scene, floor, solid(24, 32, {0.4f, 0.3f, 0.2f, 1}), {24.0 * f, 0, 24, 32});
        scene.floors[floor].lights = {{{12.0f + 24 * f, 16}, 20, {1, 1, 1}, 2}};
        EffectRef lighting;
        lighting.plugin = "acetate.lighting";
        lighting.where = "floors[" + std::to_string(f) + "].effects[0]";
        scene.floors[floor].effects = {lighting};
    }
    EffectRef bloom;
    bloom.plugin = "acetate.bloom";
    bloom.where = "global_effects[0]";
    scene.global_effects = {bloom};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    std::vector<ImageRGBA> frames;
    for (uint32_t floor : {0u, 1u, 0u}) {
        FrameStats stats;
        frames.push_back(render(*compositor, floor, &stats));
        EXPECT_EQ(stats.images_loaded + stats.targets_allocated + stats.shaders_compiled +
                      stats.pipelines_created,
                  0u)
            << "floor " << floor;
    }
    ASSERT_EQ(frames[0].pixels.size(), frames[2].pixels.size());
    EXPECT_EQ(std::memcmp(frames[0].pixels.data(), frames[2].pixels.data(),
                          frames[0].pixels.size() * sizeof(float)),
              0);
}

TEST_F(WarmSwitch, LoadReportsWhatItPrepared) {
    SceneDesc scene = make_scene(16, 16);
    const uint32_t floor = add_floor(scene, "only");
    add_tile(scene, floor, solid(16, 16, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 16, 16});
    add_tile(scene, floor, solid(16, 16, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 8, 8});
    scene.floors[floor].tiles[1].image = scene.floors[floor].tiles[0].image;  // same file twice
    // A renderer of its own: its pipeline pool starts empty, whatever ran before in-process.
    auto fresh = Renderer::create(context(), {});
    ASSERT_TRUE(fresh.ok()) << fresh.error().message;
    auto loaded = Compositor::load(*fresh.value(), scene, {});
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    auto& compositor = loaded.value();
    const LoadStats& load_stats = compositor->load_stats();
    EXPECT_EQ(load_stats.images_loaded, 1u) << "a file shared by two tiles loads once";
    // A scene without effects needs only the accumulation and the output: no floor target.
    EXPECT_EQ(load_stats.targets_allocated, 2u);
    EXPECT_EQ(compositor->targets_held().size(), 2u);
    // Direct tiles and the output stage: two pipelines from four shaders.
    EXPECT_EQ(load_stats.pipelines_created, 2u);
    EXPECT_EQ(load_stats.shaders_compiled, 4u);
}

}  // namespace
}  // namespace acetate::test

namespace acetate::test {
namespace {

TEST(Shutdown, LeavesNoVulkanObjectBehind) {
    // The validation layer reports every object still alive when the device and instance are
    // destroyed; a context of its own lets this test see those reports.
    const uint64_t before = VulkanContext::process_validation_message_count();
    {
        ContextOptions options;
        options.validation = true;
        auto context = VulkanContext::create(options);
        ASSERT_TRUE(context.ok()) << context.error().message;
        SceneDesc scene;
        scene.file = std::filesystem::temp_directory_path() / "acetate-shutdown-scene.json";
        scene.width = 8;
        scene.height = 8;
        scene.floors.resize(2);
        scene.floors[0].name = "a";
        scene.floors[1].name = "b";
        CompositorOptions compositor_options;
        compositor_options.view = OutputView::FloorAlpha;  // floor target and stencil too
        auto renderer = Renderer::create(*context.value(), {});
        ASSERT_TRUE(renderer.ok()) << renderer.error().message;
        auto compositor = Compositor::load(*renderer.value(), scene, compositor_options);
        ASSERT_TRUE(compositor.ok()) << compositor.error().message;
        ASSERT_TRUE((*compositor)->render(1).ok());
    }
    EXPECT_EQ(VulkanContext::process_validation_message_count(), before);
}

}  // namespace
}  // namespace acetate::test
