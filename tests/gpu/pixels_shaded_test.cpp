// Only the pixels a scene needs: passes are scissored to coverage, a floor hidden under opaque
// floors above does no work, and the optimised frame equals the unoptimised one.

#include "render_fixture.hpp"

namespace acetate::test {
namespace {

class PixelsShaded : public RenderTest {
  protected:
    const FloorFrameReport& floor_report(const FrameStats& stats, uint32_t floor) {
        for (const FloorFrameReport& f : stats.floors)
            if (f.floor == floor) return f;
        static FloorFrameReport none;
        ADD_FAILURE() << "no report for floor " << floor;
        return none;
    }

    CompositorOptions unoptimised() {
        CompositorOptions options;
        options.plan.scissor_to_coverage = false;
        options.plan.cull_hidden_floors = false;
        options.plan.draw_direct = false;
        return options;
    }
};

TEST_F(PixelsShaded, ATenthOfTheCanvasShadesATenthOfTheFloorPixels) {
    for (bool direct : {true, false}) {
        CompositorOptions options;
        options.plan.draw_direct = direct;
        uint64_t shaded[2];
        for (int small = 0; small < 2; ++small) {
            SceneDesc scene = make_scene(200, 100);
            const uint32_t floor = add_floor(scene, "floor");
            const double width = small ? 20 : 200;
            add_tile(scene, floor, solid(uint32_t(width), 100, {0.2f, 0.2f, 0.2f, 1}),
                     {small ? 90.0 : 0.0, 0, width, 100});
            auto compositor = load(scene, options);
            ASSERT_TRUE(compositor);
            FrameStats stats;
            render(*compositor, floor, &stats);
            shaded[small] = floor_report(stats, floor).pixels_shaded;
        }
        EXPECT_GT(shaded[0], 0u);
        EXPECT_NEAR(double(shaded[1]) / double(shaded[0]), 0.1, 0.01) << "direct=" << direct;
    }
}

TEST_F(PixelsShaded, AFloorHiddenUnderAnOpaqueFloorShadesNothing) {
    SceneDesc scene = make_scene(64, 64, {0, 0, 0, 1});
    const uint32_t ground = add_floor(scene, "ground");
    add_tile(scene, ground, solid(40, 40, {0.9f, 0.1f, 0.1f, 0.7f}), {10, 10, 40, 40});
    // Two opaque tiles above that together, and only together, hide the ground tile.
    const uint32_t middle = add_floor(scene, "middle");
    add_tile(scene, middle, solid(32, 64, {0.1f, 0.5f, 0.1f, 1}), {0, 0, 32, 64});
    const uint32_t top = add_floor(scene, "top");
    add_tile(scene, top, solid(32, 64, {0.1f, 0.1f, 0.5f, 1}), {32, 0, 32, 64});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    const ImageRGBA optimised = render(*compositor, top, &stats);
    EXPECT_EQ(floor_report(stats, ground).path, "skipped");
    EXPECT_EQ(floor_report(stats, ground).pixels_shaded, 0u);
    EXPECT_EQ(floor_report(stats, ground).passes, 0u);
    // Seen from the middle floor, the ground is only half hidden and is drawn.
    render(*compositor, middle, &stats);
    EXPECT_EQ(floor_report(stats, ground).path, "direct");

    auto reference = load(scene, unoptimised());
    ASSERT_TRUE(reference);
    const ImageRGBA full = render(*reference, top, &stats);
    // Unscissored: the tile shades its own 40x40 pixels, the composite the whole canvas.
    EXPECT_EQ(floor_report(stats, ground).pixels_shaded, 40u * 40 + 64u * 64);
    // Opaque floors on top: both frames are exactly the top floors' colours.
    EXPECT_EQ(max_abs_difference(optimised, full), 0.0);
}

TEST_F(PixelsShaded, OptimisedFrameMatchesTheUnoptimisedOne) {
    // Partial alpha, fractional and overlapping rects, a floor partly off the canvas.
    SceneDesc scene = make_scene(120, 80, {0.1f, 0.1f, 0.1f, 1});
    for (uint32_t f = 0; f < 5; ++f) {
        const uint32_t floor = add_floor(scene, "floor" + std::to_string(f));
        ImageRGBA image(24, 16);
        for (uint32_t y = 0; y < 16; ++y)
            for (uint32_t x = 0; x < 24; ++x) {
                const float a =
                    (x + y) % 5 == 0 ? 0.0f : 0.2f + 0.15f * float((x * 7 + y * 3 + f) % 6);
                float* p = image.at(x, y);
                p[0] = a * 0.9f;
                p[1] = a * 0.1f * float(f);
                p[2] = a * 0.5f;
                p[3] = a;
            }
        add_tile(scene, floor, image, {-10.0 + 27.3 * f, 5.5 + 9.25 * f, 50.5, 33.75});
    }
    auto optimised = load(scene);
    auto reference = load(scene, unoptimised());
    ASSERT_TRUE(optimised && reference);
    FrameStats fast, slow;
    const ImageRGBA a = render(*optimised, 4, &fast);
    const ImageRGBA b = render(*reference, 4, &slow);
    EXPECT_LT(fast.pixels_shaded, slow.pixels_shaded);
    // Direct drawing rounds once per floor, the target path twice (tile, then composite):
    // over 5 floors plus the output, at most 11 half-float roundings of values <= 1.
    const double tolerance = 11.0 / 1024.0;
    const double difference = max_abs_difference(a, b);
    EXPECT_LE(difference, tolerance) << "images in " << save_failure_images("optimised", a, b);
}

// A floor with an effect whose tiles lie far apart (houses on a map) shades their union, not their
// bounding box: each "result" pass and the composite draw once per rect of the union. The image is
// the one the whole-canvas frame (scissoring off) gives.
TEST_F(PixelsShaded, AnEffectOnTilesFarApartShadesTheirUnionNotTheirBoundingBox) {
    SceneDesc scene = make_scene(120, 80, {0, 0, 0, 1});
    const uint32_t floor = add_floor(scene, "houses");
    add_tile(scene, floor, solid(20, 10, {0.4f, 0.3f, 0.2f, 1}), {5, 5, 20, 10});
    add_tile(scene, floor, solid(16, 12, {0.2f, 0.3f, 0.4f, 0.5f}), {90, 60, 16, 12});
    add_tile(scene, floor, solid(10, 10, {0.3f, 0.4f, 0.2f, 0.8f}), {8, 10, 10, 10});  // overlaps
    scene.floors[floor].lights = {{{50, 40}, 90, {1, 0.9f, 0.8f}, 2.0f}};
    EffectRef lighting;
    lighting.plugin = "acetate.lighting";
    lighting.where = "floors[0].effects[0]";
    scene.floors[floor].effects = {lighting};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    const ImageRGBA image = render(*compositor, floor, &stats);
    const FloorFrameReport& report = floor_report(stats, floor);
    ASSERT_EQ(report.path, "through-target");
    // The union: 20x10 + 16x12 + the 10x10 tile less its 10x5 overlap with the first.
    const uint64_t union_pixels = 20 * 10 + 16 * 12 + 10 * 10 - 10 * 5;
    const uint64_t tile_pixels = 20 * 10 + 16 * 12 + 10 * 10;
    // Tiles, then lighting's one pass and the composite over the union (the bounding box,
    // 101x67, would be 6767 pixels a pass).
    EXPECT_EQ(report.pixels_shaded, tile_pixels + 2 * union_pixels);
    EXPECT_EQ(compositor->necessary_pixels(floor), 120u * 80 + tile_pixels + 2 * union_pixels);

    auto reference = load(scene, unoptimised());
    ASSERT_TRUE(reference);
    EXPECT_EQ(max_abs_difference(image, render(*reference, floor)), 0.0);
}

}  // namespace
}  // namespace acetate::test
