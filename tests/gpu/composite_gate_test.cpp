// The compositor's first two gates, automated: the ground floor alone, two floors with the
// ground showing through the upper floor's gaps, no white fringe at anti-aliased edges, the
// canvas background where no floor covers, and zero premultiplied violations.

#include <cmath>

#include "render_fixture.hpp"
#include "test_files.hpp"

namespace acetate::test {
namespace {

// Half-float keeps 11 significant bits: one rounding is within 2^-11 relative; we allow one
// ulp (2^-10) because Vulkan lets float16 conversion round toward zero as well as to nearest.
constexpr double kHalfUlp = 1.0 / 1024.0;

void expect_pixel(const ImageRGBA& image, uint32_t x, uint32_t y, std::array<float, 4> want,
                  double tolerance, const char* what) {
    const float* p = image.at(x, y);
    for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(p[c], want[c], tolerance)
            << what << " at (" << x << "," << y << ") channel " << c;
}

using CompositeGate = RenderTest;

TEST_F(CompositeGate, GroundFloorAloneShowsItsTilesAndTheBackgroundBeside) {
    SceneDesc scene = make_scene(64, 48, {0.2f, 0.3f, 0.4f, 1.0f});
    const uint32_t ground = add_floor(scene, "ground");
    add_tile(scene, ground, solid(40, 48, {0.5f, 0.25f, 0.125f, 1.0f}), {0, 0, 40, 48});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    const ImageRGBA out = render(*compositor, ground, &stats);
    expect_pixel(out, 10, 10, {0.5f, 0.25f, 0.125f, 1.0f}, 0, "tile");
    expect_pixel(out, 39, 47, {0.5f, 0.25f, 0.125f, 1.0f}, 0, "tile edge");
    expect_pixel(out, 40, 0, {0.2f, 0.3f, 0.4f, 1.0f}, kHalfUlp * 0.4, "background");
    expect_pixel(out, 63, 47, {0.2f, 0.3f, 0.4f, 1.0f}, kHalfUlp * 0.4, "background");
    EXPECT_EQ(stats.violations, 0u);
}

TEST_F(CompositeGate, TransparentBackgroundStaysTransparentWhereNoFloorCovers) {
    SceneDesc scene = make_scene(16, 16, {0.0f, 0.0f, 0.0f, 0.0f});
    const uint32_t ground = add_floor(scene, "ground");
    add_tile(scene, ground, solid(8, 8, {0.25f, 0.25f, 0.25f, 0.5f}), {4, 4, 8, 8});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, ground);
    expect_pixel(out, 0, 0, {0, 0, 0, 0}, 0, "uncovered");
    expect_pixel(out, 6, 6, {0.25f, 0.25f, 0.25f, 0.5f}, 0, "half-covered");
}

TEST_F(CompositeGate, GroundShowsThroughTheUpperFloorsGaps) {
    SceneDesc scene = make_scene(32, 32, {0, 0, 0, 1});
    const uint32_t ground = add_floor(scene, "ground");
    add_tile(scene, ground, solid(32, 32, {0.75f, 0.0f, 0.0f, 1.0f}), {0, 0, 32, 32});
    const uint32_t upper = add_floor(scene, "upper");
    ImageRGBA roof = solid(32, 32, {0.0f, 0.0f, 0.5f, 1.0f});
    for (uint32_t y = 8; y < 24; ++y)  // a courtyard: fully transparent
        for (uint32_t x = 8; x < 24; ++x) std::fill_n(roof.at(x, y), 4, 0.0f);
    add_tile(scene, upper, roof, {0, 0, 32, 32});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);

    FrameStats stats;
    const ImageRGBA top = render(*compositor, upper, &stats);
    expect_pixel(top, 16, 16, {0.75f, 0, 0, 1}, 0, "ground through the gap");
    expect_pixel(top, 2, 2, {0, 0, 0.5f, 1}, 0, "roof");
    EXPECT_EQ(stats.violations, 0u);
    const ImageRGBA bottom = render(*compositor, ground, &stats);
    expect_pixel(bottom, 2, 2, {0.75f, 0, 0, 1}, 0, "ground alone");
}

// Writes an 8-bit straight-alpha PNG: a dark disc whose transparent surround has WHITE straight
// colour, the classic source of white fringes when alpha conventions are mixed or when
// straight colour is filtered before premultiplication.
std::filesystem::path write_fringe_png(const std::filesystem::path& file, uint32_t size) {
    std::vector<uint8_t> pixels(size_t(size) * size * 4);
    const double c = size / 2.0, radius = size * 0.35;
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
            const double d = std::hypot(x + 0.5 - c, y + 0.5 - c);
            const double a = std::clamp(radius + 0.5 - d, 0.0, 1.0);  // 1-pixel AA ramp
            uint8_t* p = &pixels[(size_t(y) * size + x) * 4];
            const uint8_t colour = a > 0 ? 26 : 255;
            p[0] = p[1] = p[2] = colour;
            p[3] = uint8_t(std::lround(a * 255));
        }
    }
    return test::write_png8(file, size, size, pixels);
}

TEST_F(CompositeGate, NoWhiteFringeAtAntiAliasedTileEdges) {
    SceneDesc scene = make_scene(96, 96, {0, 0, 0, 1});
    const uint32_t ground = add_floor(scene, "ground");
    const float dark = srgb_to_linear(26 / 255.0f);
    add_tile(scene, ground, solid(96, 96, {dark, dark, dark, 1}), {0, 0, 96, 96});
    const uint32_t upper = add_floor(scene, "upper");
    TileDesc tile;
    tile.image = write_fringe_png(dir() / "disc.png", 32);
    tile.rect = {10.3, 7.6, 71.5, 77.25};  // scaled by a non-integer factor: filtered edges
    scene.floors[upper].tiles.push_back(tile);
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    const ImageRGBA out = render(*compositor, upper, &stats);
    // Everything on the canvas is the same dark grey, so any pixel brighter than it by more
    // than the half-float rounding of two blends came from the transparent pixels' white.
    double brightest = 0;
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x)
            brightest = std::max<double>(brightest, out.at(x, y)[0]);
    EXPECT_LE(brightest, dark * (1 + 2 * kHalfUlp)) << "white fringe";
    EXPECT_EQ(stats.violations, 0u);
}

TEST_F(CompositeGate, TileTexelsWithColourAtZeroAlphaAreReportedAndDropped) {
    // An EXR (associated alpha, taken as is) with colour where alpha is 0.
    SceneDesc scene = make_scene(16, 16, {0, 0, 0, 1});
    const uint32_t ground = add_floor(scene, "ground");
    ImageRGBA bad = solid(16, 16, {0.5f, 0.5f, 0.5f, 1});
    for (uint32_t x = 0; x < 16; ++x) {
        float* p = bad.at(x, 3);
        p[0] = 0.25f;
        p[1] = p[2] = p[3] = 0;
    }
    add_tile(scene, ground, bad, {0, 0, 16, 16});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    EXPECT_EQ(compositor->load_stats().tile_texel_violations, 16u);
    FrameStats stats;
    const ImageRGBA out = render(*compositor, ground, &stats);
    expect_pixel(out, 5, 3, {0, 0, 0, 1}, 0, "dropped texel shows the background");
    EXPECT_EQ(stats.violations, 0u) << "nothing without coverage reached the composite";
}

TEST_F(CompositeGate, ColourWithoutCoverageIsCountedAndShownInRed) {
    // Colour at alpha 0 inside the floor (docs/design.md, L-alpha-zero: as a lighting effect
    // once did). The composite counts it, and the violations view paints it red.
    SceneDesc scene = make_scene(16, 16, {0, 0, 0, 1});
    const uint32_t ground = add_floor(scene, "ground");
    ImageRGBA tile = solid(8, 8, {0.5f, 0.5f, 0.5f, 1});
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 4; x < 8; ++x) std::fill_n(tile.at(x, y), 4, 0.0f);  // a gap
    add_tile(scene, ground, tile, {4, 4, 8, 8});
    CompositorOptions options;
    options.view = OutputView::Violations;
    options.inject = CompositorOptions::Injection{{0.25f, 0, 0, 0}, true};  // inside coverage
    auto compositor = load(scene, options);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    ImageRGBA out = render(*compositor, ground, &stats);
    // Replacing a covered pixel with (0.25, 0, 0, 0): 32 covered pixels, all now violating.
    EXPECT_EQ(stats.violations, 32u);
    expect_pixel(out, 5, 5, {1, 0, 0, 1}, 0, "violation shown red");
    expect_pixel(out, 9, 5, {0, 0, 0, 1}, 0, "the gap has no coverage: black");
    // And it leaks: over with a == 0 adds the colour to whatever is below.
    compositor->set_view(OutputView::Normal);
    out = render(*compositor, ground, &stats);
    expect_pixel(out, 5, 5, {0.25f, 0, 0, 1}, 0, "leaked colour over the black background");
}

TEST_F(CompositeGate, DebugViewsShowAlphaOfFloorAndAccumulation) {
    SceneDesc scene = make_scene(16, 16, {0.1f, 0.1f, 0.1f, 1});
    const uint32_t ground = add_floor(scene, "ground");
    add_tile(scene, ground, solid(8, 16, {0.25f, 0.25f, 0.25f, 1}), {0, 0, 8, 16});
    const uint32_t upper = add_floor(scene, "upper");
    add_tile(scene, upper, solid(8, 8, {0.2f, 0.1f, 0.0f, 0.5f}), {4, 4, 8, 8});
    CompositorOptions options;
    options.view = OutputView::FloorAlpha;
    auto compositor = load(scene, options);
    ASSERT_TRUE(compositor);
    ImageRGBA out = render(*compositor, upper);
    expect_pixel(out, 6, 6, {0.5f, 0.5f, 0.5f, 1}, 0, "floor alpha inside");
    expect_pixel(out, 1, 1, {0, 0, 0, 1}, 0, "floor alpha outside (ground is another floor)");
    compositor->set_view(OutputView::AccumAlpha);
    out = render(*compositor, upper);
    expect_pixel(out, 1, 1, {1, 1, 1, 1}, 0, "accumulation alpha over the ground");
    expect_pixel(out, 10, 6, {0.5f, 0.5f, 0.5f, 1}, 0, "accumulation alpha, upper only");
    expect_pixel(out, 14, 14, {0, 0, 0, 1}, 0, "accumulation alpha, nothing");
    compositor->set_view(OutputView::FloorRgb);
    out = render(*compositor, upper);
    expect_pixel(out, 6, 6, {0.2f, 0.1f, 0.0f, 1}, kHalfUlp * 0.2, "floor rgb, alpha forced to 1");
}

}  // namespace
}  // namespace acetate::test

namespace acetate::test {
namespace {

TEST_F(CompositeGate, FloorViewOfAnEmptyFloorShowsNothingOfTheFloorsBelow) {
    SceneDesc scene = make_scene(16, 16, {0, 0, 0, 1});
    const uint32_t ground = add_floor(scene, "ground");
    add_tile(scene, ground, solid(16, 16, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 16, 16});
    const uint32_t empty = add_floor(scene, "empty");  // no tiles at all
    CompositorOptions options;
    options.view = OutputView::FloorAlpha;
    options.plan.draw_direct = false;  // the ground goes through the shared floor target
    auto compositor = load(scene, options);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, empty);
    expect_pixel(out, 8, 8, {0, 0, 0, 1}, 0, "the empty floor's alpha");
}

TEST_F(CompositeGate, ColourOutsideCoverageIsNotCountedBecauseTheGateDropsIt) {
    SceneDesc scene = make_scene(16, 16, {0, 0, 0, 1});
    const uint32_t ground = add_floor(scene, "ground");
    add_tile(scene, ground, solid(4, 4, {0.5f, 0.5f, 0.5f, 1}), {6, 6, 4, 4});
    CompositorOptions options;
    options.inject = CompositorOptions::Injection{{0.25f, 0, 0, 0}, false};  // outside coverage
    options.plan.scissor_to_coverage = false;  // the composite runs over the whole canvas
    auto compositor = load(scene, options);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    const ImageRGBA out = render(*compositor, ground, &stats);
    EXPECT_EQ(stats.violations, 0u) << "fragments the stencil rejects never ran the shader";
    expect_pixel(out, 0, 0, {0, 0, 0, 1}, 0, "nothing reached the accumulation");
}

}  // namespace
}  // namespace acetate::test
