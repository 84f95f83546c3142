// Floor isolation: a floor's pixels never appear where only other floors cover, and the
// composite's stencil really gates what reaches the accumulation.

#include "render_fixture.hpp"

namespace acetate::test {
namespace {

using FloorIsolation = RenderTest;

TEST_F(FloorIsolation, EachFloorsColourStaysInsideItsOwnCoverage) {
    // Three floors, each a pure primary in its own third, overlapping nowhere.
    SceneDesc scene = make_scene(90, 30, {0, 0, 0, 0});
    const std::array<std::array<float, 4>, 3> colours = {
        {{0.8f, 0, 0, 1}, {0, 0.8f, 0, 0.6f}, {0, 0, 0.8f, 0.9f}}};
    for (uint32_t f = 0; f < 3; ++f) {
        const uint32_t floor = add_floor(scene, "floor" + std::to_string(f));
        add_tile(scene, floor, solid(30, 30, colours[f]), {30.0 * f, 0, 30, 30});
    }
    for (bool direct : {true, false}) {
        CompositorOptions options;
        options.plan.draw_direct = direct;
        auto compositor = load(scene, options);
        ASSERT_TRUE(compositor);
        const ImageRGBA out = render(*compositor, 2);
        for (uint32_t y = 0; y < 30; ++y) {
            for (uint32_t x = 0; x < 90; ++x) {
                const uint32_t owner = x / 30;
                for (uint32_t c = 0; c < 3; ++c) {
                    if (c == owner) continue;
                    ASSERT_EQ(out.at(x, y)[c], 0.0f)
                        << "floor " << c << "'s colour at (" << x << "," << y
                        << ") where only floor " << owner << " covers (direct=" << direct << ")";
                }
            }
        }
    }
}

TEST_F(FloorIsolation, IsolationViewTintsEveryFloorItsOwnColour) {
    SceneDesc scene = make_scene(60, 20, {0, 0, 0, 1});
    for (uint32_t f = 0; f < 2; ++f) {
        const uint32_t floor = add_floor(scene, "floor" + std::to_string(f));
        add_tile(scene, floor, solid(30, 20, {1, 1, 1, 1}), {30.0 * f, 0, 30, 20});
    }
    CompositorOptions options;
    options.view = OutputView::Isolation;
    auto compositor = load(scene, options);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, 1);
    for (uint32_t f = 0; f < 2; ++f) {
        const auto tint = isolation_tint(f);
        const float* p = out.at(30 * f + 15, 10);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(p[c], tint[c], 1.0 / 512) << "floor " << f << " channel " << c;
    }
    EXPECT_NE(isolation_tint(0), isolation_tint(1));
}

TEST_F(FloorIsolation, StencilKeepsColourOutsideCoverageOutOfTheAccumulation) {
    // The fill hook paints magenta into the floor target wherever the floor does NOT cover,
    // as a contract-breaking effect would. The stencil-gated composite must drop all of it.
    SceneDesc scene = make_scene(32, 32, {0, 0, 0, 0});
    const uint32_t ground = add_floor(scene, "ground");
    add_tile(scene, ground, solid(16, 16, {0.1f, 0.2f, 0.3f, 1}), {8, 8, 16, 16});
    CompositorOptions options;
    options.inject = CompositorOptions::Injection{{1, 0, 1, 1}, false};
    options.plan.scissor_to_coverage = false;  // let the gate, not the scissor, do the work
    auto compositor = load(scene, options);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, ground);
    for (uint32_t y = 0; y < 32; ++y) {
        for (uint32_t x = 0; x < 32; ++x) {
            const bool covered = x >= 8 && x < 24 && y >= 8 && y < 24;
            const float* p = out.at(x, y);
            if (covered) {
                // The tile's own colour, to half precision (one rounding, 2^-10 relative).
                ASSERT_NEAR(p[2], 0.3f, 0.3 / 1024) << "tile at " << x << "," << y;
                ASSERT_EQ(p[3], 1.0f);
            } else {
                ASSERT_EQ(p[0], 0.0f)
                    << "uncovered colour reached the accumulation at " << x << "," << y;
                ASSERT_EQ(p[3], 0.0f);
            }
        }
    }
    // Control: the magenta really is in the floor target (else the test above proves nothing).
    compositor->set_view(OutputView::FloorRgb);
    const ImageRGBA floor_rgb = render(*compositor, ground);
    EXPECT_EQ(floor_rgb.at(0, 0)[0], 1.0f);
    EXPECT_EQ(floor_rgb.at(0, 0)[2], 1.0f);
}

}  // namespace
}  // namespace acetate::test
