// Unit tests (no GPU) for the pixel-rect helpers and the frame planner.

#include "render/frame_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <vector>

#include "core/pixel_rect.hpp"

namespace acetate {

// Readable failures: "{x0,y0 .. x1,y1}" instead of raw bytes.
void PrintTo(const PixelRect& r, std::ostream* os) {
    *os << "{" << r.x0 << "," << r.y0 << " .. " << r.x1 << "," << r.y1 << "}";
}
void PrintTo(FloorPath path, std::ostream* os) {
    *os << to_string(path);
}

namespace {

constexpr const char* kHidden = "hidden under opaque floors above";

// ---------------------------------------------------------------------------------------------
// pixels_covered: pixel i is covered iff its centre i + 0.5 lies in [x, x + w) (same for y),
// clipped to the canvas.

TEST(PixelsCovered, WholePixelRectCoversExactlyItsPixels) {
    EXPECT_EQ(pixels_covered(2, 3, 4, 5, 64, 32), (PixelRect{2, 3, 6, 8}));
    EXPECT_EQ(pixels_covered(0, 0, 64, 32, 64, 32), (PixelRect{0, 0, 64, 32}));
    EXPECT_EQ(pixels_covered(0, 0, 64, 32, 64, 32).area(), 64u * 32u);
}

TEST(PixelsCovered, CentreOnTheLeftEdgeIsInside) {
    // [0.5, 1.5): pixel 0's centre 0.5 is on the closed left edge (covered); pixel 1's centre
    // 1.5 is on the open right edge (not covered).
    EXPECT_EQ(pixels_covered(0.5, 0.5, 1, 1, 8, 8), (PixelRect{0, 0, 1, 1}));
}

TEST(PixelsCovered, FractionalRectJustPastACentreCoversTheNextPixel) {
    // [0.6, 1.6): only pixel 1 (centre 1.5).
    EXPECT_EQ(pixels_covered(0.6, 0.6, 1, 1, 8, 8), (PixelRect{1, 1, 2, 2}));
    // [0.4, 1.4): only pixel 0 (centre 0.5).
    EXPECT_EQ(pixels_covered(0.4, 0.4, 1, 1, 8, 8), (PixelRect{0, 0, 1, 1}));
}

TEST(PixelsCovered, NarrowRectAroundACentreCoversOnePixel) {
    // [2.4, 2.6) contains 2.5 only.
    EXPECT_EQ(pixels_covered(2.4, 5.45, 0.2, 0.1, 8, 8), (PixelRect{2, 5, 3, 6}));
}

TEST(PixelsCovered, NarrowRectBetweenCentresCoversNothing) {
    // [0.6, 0.9) holds no pixel centre.
    EXPECT_TRUE(pixels_covered(0.6, 0, 0.3, 4, 8, 8).empty());
    EXPECT_TRUE(pixels_covered(0, 0.6, 4, 0.3, 8, 8).empty());
    EXPECT_EQ(pixels_covered(0.6, 0, 0.3, 4, 8, 8).area(), 0u);
}

TEST(PixelsCovered, FractionalBoundsOnBothSides) {
    // x: [1.25, 4.75) holds centres 1.5, 2.5, 3.5, 4.5 -> pixels 1..4.
    // y: [0.5, 3.5) holds centres 0.5, 1.5, 2.5 (3.5 is on the open edge) -> pixels 0..2.
    EXPECT_EQ(pixels_covered(1.25, 0.5, 3.5, 3.0, 16, 16), (PixelRect{1, 0, 5, 3}));
}

TEST(PixelsCovered, ClipsToTheCanvas) {
    // [-3.2, 1.8) holds centres -2.5 .. 1.5; on the canvas that is pixels 0 and 1.
    EXPECT_EQ(pixels_covered(-3.2, -3.2, 5, 5, 64, 32), (PixelRect{0, 0, 2, 2}));
    // Past the right and bottom edges.
    EXPECT_EQ(pixels_covered(60, 30, 10, 10, 64, 32), (PixelRect{60, 30, 64, 32}));
    // Larger than the canvas on every side.
    EXPECT_EQ(pixels_covered(-100, -100, 1000, 1000, 64, 32), (PixelRect{0, 0, 64, 32}));
}

TEST(PixelsCovered, RectsFullyOutsideTheCanvasAreEmpty) {
    EXPECT_TRUE(pixels_covered(100, 0, 10, 10, 64, 32).empty());    // right
    EXPECT_TRUE(pixels_covered(0, 40, 10, 10, 64, 32).empty());     // below
    EXPECT_TRUE(pixels_covered(-10, 0, 5, 10, 64, 32).empty());     // left
    EXPECT_TRUE(pixels_covered(0, -10, 10, 5, 64, 32).empty());     // above
    EXPECT_TRUE(pixels_covered(64, 0, 10, 10, 64, 32).empty());     // starts on the right edge
    EXPECT_TRUE(pixels_covered(-10, 0, 10, 10, 64, 32).empty());    // ends on the left edge
    EXPECT_TRUE(pixels_covered(-10, 0, 10.4, 10, 64, 32).empty());  // ends before centre 0.5
    EXPECT_TRUE(pixels_covered(63.6, 0, 10, 10, 64, 32).empty());   // starts past centre 63.5
    EXPECT_EQ(pixels_covered(100, 100, 10, 10, 64, 32).area(), 0u);
}

TEST(PixelsCovered, JustReachingTheFirstCentreCoversIt) {
    // [-10, 0.5) holds no centre; [-10, 0.51) holds 0.5.
    EXPECT_TRUE(pixels_covered(-10, 0, 10.5, 4, 64, 32).empty());
    EXPECT_EQ(pixels_covered(-10, 0, 10.51, 4, 64, 32), (PixelRect{0, 0, 1, 4}));
}

// ---------------------------------------------------------------------------------------------
// intersect / bounding_union

TEST(PixelRectOps, IntersectAndBoundingUnion) {
    EXPECT_EQ(intersect({0, 0, 10, 10}, {5, 5, 20, 20}), (PixelRect{5, 5, 10, 10}));
    EXPECT_TRUE(intersect({0, 0, 10, 10}, {10, 0, 20, 10}).empty());  // touching edges
    EXPECT_EQ(bounding_union({0, 0, 2, 2}, {8, 8, 10, 10}), (PixelRect{0, 0, 10, 10}));
    EXPECT_EQ(bounding_union(PixelRect{}, {3, 4, 5, 6}), (PixelRect{3, 4, 5, 6}));
    EXPECT_EQ(bounding_union({3, 4, 5, 6}, PixelRect{}), (PixelRect{3, 4, 5, 6}));
}

// ---------------------------------------------------------------------------------------------
// covered_by_union

TEST(CoveredByUnion, TwoHalvesCoverExactly) {
    const PixelRect target{0, 0, 8, 8};
    EXPECT_TRUE(covered_by_union(target, {{0, 0, 4, 8}, {4, 0, 8, 8}}));
    EXPECT_TRUE(covered_by_union(target, {{0, 4, 8, 8}, {0, 0, 8, 4}}));
}

TEST(CoveredByUnion, TwoHalvesWithAGapOrShortfallDoNotCover) {
    const PixelRect target{0, 0, 8, 8};
    EXPECT_FALSE(covered_by_union(target, {{0, 0, 4, 8}, {5, 0, 8, 8}}));  // column 4 missing
    EXPECT_FALSE(covered_by_union(target, {{0, 0, 4, 8}, {4, 0, 8, 7}}));  // one row short
    EXPECT_FALSE(covered_by_union(target, {{0, 0, 4, 8}}));                // one half only
}

TEST(CoveredByUnion, OnePixelHoleIsNotCovered) {
    const PixelRect target{0, 0, 8, 8};
    // Four rects around pixel (3, 3).
    std::vector<PixelRect> cover{{0, 0, 8, 3}, {0, 4, 8, 8}, {0, 3, 3, 4}, {4, 3, 8, 4}};
    EXPECT_FALSE(covered_by_union(target, cover));
    cover.push_back({3, 3, 4, 4});
    EXPECT_TRUE(covered_by_union(target, cover));
}

TEST(CoveredByUnion, OverlappingAndLargerCoversCount) {
    const PixelRect target{10, 10, 20, 20};
    EXPECT_TRUE(covered_by_union(target, {{0, 0, 100, 100}}));
    EXPECT_TRUE(covered_by_union(target, {{0, 0, 16, 100}, {12, 0, 30, 100}}));
    EXPECT_TRUE(covered_by_union(target, {{5, 5, 15, 25}, {14, 5, 25, 15}, {14, 14, 25, 25}}));
    EXPECT_FALSE(covered_by_union(target, {{5, 5, 15, 25}, {14, 5, 25, 15}, {16, 14, 25, 25}}));
}

TEST(CoveredByUnion, EmptyCover) {
    EXPECT_FALSE(covered_by_union({0, 0, 1, 1}, {}));
    EXPECT_FALSE(covered_by_union({0, 0, 8, 8}, {PixelRect{}}));
    // Rects that miss the target entirely.
    EXPECT_FALSE(covered_by_union({0, 0, 8, 8}, {{8, 0, 16, 8}, {0, 8, 8, 16}}));
}

TEST(CoveredByUnion, EmptyTargetIsAlwaysCovered) {
    EXPECT_TRUE(covered_by_union(PixelRect{}, {}));
    EXPECT_TRUE(covered_by_union(PixelRect{5, 5, 5, 9}, {}));
}

// ---------------------------------------------------------------------------------------------
// plan_frame

constexpr uint32_t kW = 64, kH = 32;
const PixelRect kCanvas{0, 0, kW, kH};

FloorGeometry floor_of(PixelRect coverage, std::vector<PixelRect> opaque = {},
                       bool needs_target = false) {
    FloorGeometry g;
    g.coverage = coverage;
    g.opaque = std::move(opaque);
    g.needs_target = needs_target;
    return g;
}

// A floor whose one tile is opaque everywhere.
FloorGeometry opaque_floor(PixelRect rect) {
    return floor_of(rect, {rect});
}

TEST(PlanFrame, PlansFloorsZeroToActiveBottomToTop) {
    const std::vector<FloorGeometry> floors{floor_of({0, 0, 64, 32}), floor_of({8, 4, 24, 20}),
                                            floor_of({1, 1, 2, 2}), floor_of({3, 3, 9, 9})};
    const FramePlan plan = plan_frame(kW, kH, floors, 2, PlanOptions{});
    ASSERT_EQ(plan.steps.size(), 3u);
    for (uint32_t i = 0; i < 3; ++i) {
        EXPECT_EQ(plan.steps[i].floor, i);
        EXPECT_EQ(plan.steps[i].path, FloorPath::Direct) << "floor " << i;
    }
}

TEST(PlanFrame, FloorsAboveActiveAreNotPlannedAndDoNotHide) {
    // Floor 2 would hide everything, but it is above the active floor.
    const std::vector<FloorGeometry> floors{floor_of({0, 0, 64, 32}), floor_of({8, 4, 24, 20}),
                                            opaque_floor(kCanvas)};
    const FramePlan plan = plan_frame(kW, kH, floors, 1, PlanOptions{});
    ASSERT_EQ(plan.steps.size(), 2u);
    EXPECT_EQ(plan.steps[0].path, FloorPath::Direct);
    EXPECT_EQ(plan.steps[1].path, FloorPath::Direct);

    const FramePlan only_ground = plan_frame(kW, kH, floors, 0, PlanOptions{});
    ASSERT_EQ(only_ground.steps.size(), 1u);
    EXPECT_EQ(only_ground.steps[0].floor, 0u);
    EXPECT_EQ(only_ground.steps[0].path, FloorPath::Direct);
}

TEST(PlanFrame, FloorWithEmptyCoverageIsSkipped) {
    const std::vector<FloorGeometry> floors{floor_of(kCanvas), floor_of(PixelRect{}),
                                            floor_of(PixelRect{}, {}, true)};
    const FramePlan plan = plan_frame(kW, kH, floors, 2, PlanOptions{});
    ASSERT_EQ(plan.steps.size(), 3u);
    EXPECT_EQ(plan.steps[0].path, FloorPath::Direct);
    EXPECT_EQ(plan.steps[1].path, FloorPath::Skipped);
    EXPECT_FALSE(plan.steps[1].why.empty());
    EXPECT_NE(plan.steps[1].why, kHidden);
    // Even a floor with effects is skipped when it covers nothing.
    EXPECT_EQ(plan.steps[2].path, FloorPath::Skipped);
}

TEST(PlanFrame, FloorFullyUnderAnOpaqueFloorIsSkipped) {
    const std::vector<FloorGeometry> floors{floor_of({10, 10, 20, 20}),
                                            opaque_floor({8, 8, 24, 24})};
    const FramePlan plan = plan_frame(kW, kH, floors, 1, PlanOptions{});
    ASSERT_EQ(plan.steps.size(), 2u);
    EXPECT_EQ(plan.steps[0].path, FloorPath::Skipped);
    EXPECT_EQ(plan.steps[0].why, kHidden);
    EXPECT_EQ(plan.steps[1].path, FloorPath::Direct);
}

TEST(PlanFrame, HiddenFloorWithEffectsIsAlsoSkipped) {
    const std::vector<FloorGeometry> floors{floor_of({10, 10, 20, 20}, {}, true),
                                            opaque_floor(kCanvas)};
    const FramePlan plan = plan_frame(kW, kH, floors, 1, PlanOptions{});
    EXPECT_EQ(plan.steps[0].path, FloorPath::Skipped);
    EXPECT_EQ(plan.steps[0].why, kHidden);
}

TEST(PlanFrame, HiddenByAnyOpaqueFloorAboveNotOnlyTheNextOne) {
    // Floor 1 is transparent, floor 2 is opaque over floor 0's coverage.
    const std::vector<FloorGeometry> floors{floor_of({10, 10, 20, 20}), floor_of({0, 0, 4, 4}),
                                            opaque_floor({0, 0, 32, 32})};
    const FramePlan plan = plan_frame(kW, kH, floors, 2, PlanOptions{});
    EXPECT_EQ(plan.steps[0].path, FloorPath::Skipped);
    EXPECT_EQ(plan.steps[0].why, kHidden);
    EXPECT_EQ(plan.steps[1].path, FloorPath::Skipped);  // also under floor 2
    EXPECT_EQ(plan.steps[2].path, FloorPath::Direct);
}

TEST(PlanFrame, NotCulledWhenCullingIsOff) {
    const std::vector<FloorGeometry> floors{floor_of({10, 10, 20, 20}),
                                            opaque_floor({8, 8, 24, 24})};
    PlanOptions options;
    options.cull_hidden_floors = false;
    const FramePlan plan = plan_frame(kW, kH, floors, 1, options);
    EXPECT_EQ(plan.steps[0].path, FloorPath::Direct);
    EXPECT_NE(plan.steps[0].why, kHidden);
}

TEST(PlanFrame, ForceTargetFloorIsNeverCulled) {
    const std::vector<FloorGeometry> floors{floor_of({10, 10, 20, 20}),
                                            opaque_floor({8, 8, 24, 24})};
    PlanOptions options;
    options.force_target_floor = 0;
    const FramePlan plan = plan_frame(kW, kH, floors, 1, options);
    EXPECT_EQ(plan.steps[0].path, FloorPath::ThroughTarget);
    EXPECT_NE(plan.steps[0].why, kHidden);
    EXPECT_EQ(plan.steps[1].path, FloorPath::Direct);
}

TEST(PlanFrame, PartiallyHiddenFloorIsNotSkipped) {
    // The opaque floor above misses the coverage by one column.
    const std::vector<FloorGeometry> floors{floor_of({10, 10, 20, 20}),
                                            opaque_floor({8, 8, 19, 24})};
    const FramePlan plan = plan_frame(kW, kH, floors, 1, PlanOptions{});
    EXPECT_EQ(plan.steps[0].path, FloorPath::Direct);
}

TEST(PlanFrame, TransparentCoverageAboveDoesNotHide) {
    // Floor 1 covers floor 0 but has no opaque tiles.
    const std::vector<FloorGeometry> floors{floor_of({10, 10, 20, 20}), floor_of(kCanvas)};
    const FramePlan plan = plan_frame(kW, kH, floors, 1, PlanOptions{});
    EXPECT_EQ(plan.steps[0].path, FloorPath::Direct);
}

TEST(PlanFrame, OpaqueCoverageSplitAcrossTwoFloorsAboveStillHides) {
    // Floor 1 hides the left half of floor 0, floor 2 the right half.
    const std::vector<FloorGeometry> floors{
        floor_of({10, 10, 20, 20}), opaque_floor({0, 0, 15, 32}), opaque_floor({15, 0, 64, 32})};
    const FramePlan plan = plan_frame(kW, kH, floors, 2, PlanOptions{});
    ASSERT_EQ(plan.steps.size(), 3u);
    EXPECT_EQ(plan.steps[0].path, FloorPath::Skipped);
    EXPECT_EQ(plan.steps[0].why, kHidden);
    EXPECT_EQ(plan.steps[1].path, FloorPath::Direct);
    EXPECT_EQ(plan.steps[2].path, FloorPath::Direct);

    // With a one-pixel gap between the halves, floor 0 shows through.
    const std::vector<FloorGeometry> gap{floor_of({10, 10, 20, 20}), opaque_floor({0, 0, 15, 32}),
                                         opaque_floor({16, 0, 64, 32})};
    EXPECT_EQ(plan_frame(kW, kH, gap, 2, PlanOptions{}).steps[0].path, FloorPath::Direct);
}

TEST(PlanFrame, OpaqueTilesOfOneFloorAboveCombine) {
    // Floor 1 has two opaque tiles, each hiding a half of floor 0; its coverage is their bounds.
    const std::vector<FloorGeometry> floors{
        floor_of({10, 10, 20, 20}),
        floor_of({10, 10, 20, 20}, {{10, 10, 15, 20}, {15, 10, 20, 20}})};
    const FramePlan plan = plan_frame(kW, kH, floors, 1, PlanOptions{});
    EXPECT_EQ(plan.steps[0].path, FloorPath::Skipped);
    EXPECT_EQ(plan.steps[0].why, kHidden);
}

TEST(PlanFrame, AFloorsOwnOpaqueTilesDoNotHideItself) {
    const std::vector<FloorGeometry> floors{opaque_floor(kCanvas)};
    const FramePlan plan = plan_frame(kW, kH, floors, 0, PlanOptions{});
    ASSERT_EQ(plan.steps.size(), 1u);
    EXPECT_EQ(plan.steps[0].path, FloorPath::Direct);
}

TEST(PlanFrame, OpaqueFloorsBelowDoNotHideFloorsAbove) {
    const std::vector<FloorGeometry> floors{opaque_floor(kCanvas), floor_of({10, 10, 20, 20})};
    const FramePlan plan = plan_frame(kW, kH, floors, 1, PlanOptions{});
    EXPECT_EQ(plan.steps[0].path, FloorPath::Direct);
    EXPECT_EQ(plan.steps[1].path, FloorPath::Direct);
}

TEST(PlanFrame, FloorWithEffectsGoesThroughItsTarget) {
    const std::vector<FloorGeometry> floors{floor_of(kCanvas), floor_of({8, 4, 24, 20}, {}, true)};
    const FramePlan plan = plan_frame(kW, kH, floors, 1, PlanOptions{});
    EXPECT_EQ(plan.steps[0].path, FloorPath::Direct);
    EXPECT_EQ(plan.steps[1].path, FloorPath::ThroughTarget);
    EXPECT_FALSE(plan.steps[1].why.empty());
}

TEST(PlanFrame, DrawDirectOffSendsEveryDrawnFloorThroughItsTarget) {
    const std::vector<FloorGeometry> floors{floor_of(kCanvas), floor_of({8, 4, 24, 20}),
                                            floor_of(PixelRect{})};
    PlanOptions options;
    options.draw_direct = false;
    const FramePlan plan = plan_frame(kW, kH, floors, 2, options);
    EXPECT_EQ(plan.steps[0].path, FloorPath::ThroughTarget);
    EXPECT_EQ(plan.steps[1].path, FloorPath::ThroughTarget);
    EXPECT_EQ(plan.steps[2].path, FloorPath::Skipped);  // still nothing to draw
}

TEST(PlanFrame, ForceTargetFloorGoesThroughItsTargetOthersDirect) {
    const std::vector<FloorGeometry> floors{floor_of(kCanvas), floor_of({8, 4, 24, 20}),
                                            floor_of({1, 1, 5, 5})};
    PlanOptions options;
    options.force_target_floor = 1;
    const FramePlan plan = plan_frame(kW, kH, floors, 2, options);
    EXPECT_EQ(plan.steps[0].path, FloorPath::Direct);
    EXPECT_EQ(plan.steps[1].path, FloorPath::ThroughTarget);
    EXPECT_EQ(plan.steps[2].path, FloorPath::Direct);

    // A forced floor above the active one changes nothing.
    options.force_target_floor = 2;
    const FramePlan lower = plan_frame(kW, kH, floors, 1, options);
    ASSERT_EQ(lower.steps.size(), 2u);
    EXPECT_EQ(lower.steps[0].path, FloorPath::Direct);
    EXPECT_EQ(lower.steps[1].path, FloorPath::Direct);
}

TEST(PlanFrame, ScissorIsTheCoverage) {
    const std::vector<FloorGeometry> floors{floor_of(kCanvas), floor_of({8, 4, 24, 20}),
                                            floor_of({3, 5, 7, 9}, {}, true)};
    const FramePlan plan = plan_frame(kW, kH, floors, 2, PlanOptions{});
    EXPECT_EQ(plan.steps[0].scissor, kCanvas);
    EXPECT_EQ(plan.steps[1].scissor, (PixelRect{8, 4, 24, 20}));
    EXPECT_EQ(plan.steps[2].scissor, (PixelRect{3, 5, 7, 9}));
}

TEST(PlanFrame, ScissorIsTheCanvasWhenNotScissoringToCoverage) {
    const std::vector<FloorGeometry> floors{floor_of(kCanvas), floor_of({8, 4, 24, 20}),
                                            floor_of({3, 5, 7, 9}, {}, true)};
    PlanOptions options;
    options.scissor_to_coverage = false;
    const FramePlan plan = plan_frame(kW, kH, floors, 2, options);
    for (const FloorStep& step : plan.steps) EXPECT_EQ(step.scissor, kCanvas) << step.floor;
    EXPECT_EQ(plan.steps[1].path, FloorPath::Direct);
    EXPECT_EQ(plan.steps[2].path, FloorPath::ThroughTarget);
}

TEST(PlanFrame, ToStringNamesEveryPath) {
    EXPECT_STREQ(to_string(FloorPath::Skipped), "skipped");
    EXPECT_STREQ(to_string(FloorPath::Direct), "direct");
    EXPECT_STREQ(to_string(FloorPath::ThroughTarget), "through-target");
}

// disjoint_union: every pixel of the union in exactly one rect, none outside it, checked pixel by
// pixel against the input rects on small grids.
void expect_exact_disjoint_cover(const std::vector<PixelRect>& rects) {
    const std::vector<PixelRect> cover = disjoint_union(rects);
    uint64_t union_pixels = 0;
    for (int64_t y = -2; y < 24; ++y)
        for (int64_t x = -2; x < 24; ++x) {
            auto inside = [&](const PixelRect& r) {
                return r.x0 <= x && x < r.x1 && r.y0 <= y && y < r.y1;
            };
            const bool in_union = std::any_of(rects.begin(), rects.end(), inside);
            const auto hits = std::count_if(cover.begin(), cover.end(), inside);
            ASSERT_EQ(hits, in_union ? 1 : 0) << "pixel " << x << "," << y;
            union_pixels += in_union;
        }
    EXPECT_EQ(union_area(rects), union_pixels);
}

TEST(DisjointUnion, CoversTheUnionExactlyOnce) {
    expect_exact_disjoint_cover({});
    expect_exact_disjoint_cover({{2, 3, 9, 7}});
    expect_exact_disjoint_cover({{0, 0, 4, 4}, {12, 10, 20, 20}});             // far apart
    expect_exact_disjoint_cover({{0, 0, 10, 10}, {5, 5, 15, 15}});             // overlapping
    expect_exact_disjoint_cover({{0, 0, 20, 4}, {0, 0, 4, 20}});               // an L
    expect_exact_disjoint_cover({{1, 1, 5, 5}, {1, 1, 5, 5}, {3, 0, 4, 22}});  // duplicates
    expect_exact_disjoint_cover({{0, 0, 0, 5}, {4, 4, 6, 6}});                 // an empty rect
}

TEST(DisjointUnion, KeepsARectOrAColumnOfRectsWhole) {
    EXPECT_EQ(disjoint_union({{2, 3, 9, 7}}), (std::vector<PixelRect>{{2, 3, 9, 7}}));
    // Two rects stacked with the same x span become one.
    EXPECT_EQ(disjoint_union({{0, 0, 8, 4}, {0, 4, 8, 9}}), (std::vector<PixelRect>{{0, 0, 8, 9}}));
    // Three houses apart: three rects, their area and no more.
    const std::vector<PixelRect> houses{
        {150, 96, 502, 360}, {660, 60, 836, 300}, {560, 350, 800, 490}};
    EXPECT_EQ(disjoint_union(houses).size(), 3u);
    EXPECT_EQ(union_area(houses), 352u * 264 + 176u * 240 + 240u * 140);
}

}  // namespace
}  // namespace acetate
