// The frame graph's compiler (host/render/frame_graph.hpp), without a device: which passes run,
// which barriers each needs, and each image's first and last use.
#include "render/frame_graph.hpp"

#include <gtest/gtest.h>

namespace acetate {
namespace {

using A = ImageAccess;

FramePassDecl pass(std::string name, std::vector<ImageUse> uses, bool sink = false) {
    return {std::move(name), std::move(uses), sink};
}

// The names of the passes that run, in order.
std::vector<std::string> run(const FrameGraphPlan& plan, const std::vector<FramePassDecl>& p) {
    std::vector<std::string> out;
    for (uint32_t index : plan.passes) out.push_back(p[index].name);
    return out;
}

// The images that get a barrier before run pass `i`, with the access each goes to.
std::vector<std::pair<uint32_t, A>> barriers(const FrameGraphPlan& plan, size_t i) {
    std::vector<std::pair<uint32_t, A>> out;
    for (const ImageBarrier& b : plan.barriers[i]) out.emplace_back(b.image, b.next);
    return out;
}

TEST(FrameGraph, APassWhoseWritesNobodyReadsIsCulledAndAChainToTheOutputIsKept) {
    // 0: the output; 1 -> 2 feeds it; 3 is written and never read.
    const std::vector<FramePassDecl> p{
        pass("draw 1", {{1, A::ColourWrite}}),
        pass("dead 3", {{3, A::ColourWrite}}),
        pass("1 to 2", {{1, A::Sampled}, {2, A::ColourWrite}}),
        pass("output", {{2, A::Sampled}, {0, A::ColourWrite}}),
    };
    const FrameGraphPlan plan = compile_frame_graph(p, {true, false, false, false});
    EXPECT_EQ(run(plan, p), (std::vector<std::string>{"draw 1", "1 to 2", "output"}));
    EXPECT_EQ(plan.culled, std::vector<uint32_t>{1});
    EXPECT_FALSE(plan.lifetimes[3].used());
}

TEST(FrameGraph, ImagesReadAfterTheFrameAndSinksKeepTheirWriters) {
    const std::vector<FramePassDecl> p{
        pass("kept for a read-back", {{1, A::ColourWrite}}),
        pass("sink", {{2, A::ColourWrite}}, true),
        pass("dead", {{3, A::ColourWrite}}),
    };
    const FrameGraphPlan plan = compile_frame_graph(p, {false, true, false, false});
    EXPECT_EQ(run(plan, p), (std::vector<std::string>{"kept for a read-back", "sink"}));
}

TEST(FrameGraph, AWholeClearEndsTheNeedForWhatWasWrittenBefore) {
    // Image 1 is drawn, then cleared whole before anything reads it: the draw is dead. A draw
    // that loads over it (a colour attachment reads what it holds) keeps the one before.
    const std::vector<FramePassDecl> p{
        pass("draw, then cleared", {{1, A::ColourWrite}}),
        pass("clear", {{1, A::TransferWrite}}),
        pass("draw", {{1, A::ColourWrite}}),
        pass("blend over it", {{1, A::ColourWrite}}),
        pass("output", {{1, A::Sampled}, {0, A::ColourWrite}}, true),
    };
    const FrameGraphPlan plan = compile_frame_graph(p, {true, false});
    EXPECT_EQ(run(plan, p), (std::vector<std::string>{"clear", "draw", "blend over it", "output"}));
}

TEST(FrameGraph, APingPongStepTransitionsBothImagesInOneBarrier) {
    // An effect chain: 1 is drawn, then read while 2 is drawn, then 2 read while 1 is drawn.
    const std::vector<FramePassDecl> p{
        pass("tiles", {{1, A::ColourWrite}}),
        pass("effect a", {{1, A::Sampled}, {2, A::ColourWrite}}),
        pass("effect b", {{2, A::Sampled}, {1, A::ColourWrite}}),
        pass("output", {{1, A::Sampled}, {0, A::ColourWrite}}),
    };
    const FrameGraphPlan plan = compile_frame_graph(p, {true, false, false});
    ASSERT_EQ(plan.passes.size(), 4u);
    using B = std::vector<std::pair<uint32_t, A>>;
    EXPECT_EQ(barriers(plan, 0), (B{{1, A::ColourWrite}}));
    EXPECT_EQ(barriers(plan, 1), (B{{1, A::Sampled}, {2, A::ColourWrite}}));
    EXPECT_EQ(barriers(plan, 2), (B{{2, A::Sampled}, {1, A::ColourWrite}}));
    EXPECT_EQ(barriers(plan, 3), (B{{1, A::Sampled}, {0, A::ColourWrite}}));
    EXPECT_EQ(plan.barrier_batches(), 4u);  // one command per pass, however many images
    // The first use comes from the image's state before the frame.
    EXPECT_EQ(plan.barriers[0][0].last, A::None);
    EXPECT_EQ(plan.barriers[1][1].last, A::None);
    EXPECT_EQ(plan.barriers[2][1].last, A::Sampled);
}

TEST(FrameGraph, ReadsAfterReadsInOneLayoutNeedNoBarrier) {
    const std::vector<FramePassDecl> p{
        pass("draw", {{1, A::ColourWrite}}),
        pass("read once", {{1, A::Sampled}, {2, A::ColourWrite}}),
        pass("read again", {{1, A::Sampled}, {3, A::ColourWrite}}),
    };
    const FrameGraphPlan plan = compile_frame_graph(p, {false, false, true, true});
    using B = std::vector<std::pair<uint32_t, A>>;
    EXPECT_EQ(barriers(plan, 2), (B{{3, A::ColourWrite}}));
}

TEST(FrameGraph, WritesAfterWritesAndWritesAfterReadsInOneLayoutGetABarrier) {
    // Two rendering passes into one attachment; a stencil written, then tested, then written
    // again (one layout throughout, so only the hazards ask for the barriers).
    const std::vector<FramePassDecl> p{
        pass("first draw", {{1, A::ColourWrite}, {2, A::StencilWrite}}),
        pass("second draw", {{1, A::ColourWrite}}),
        pass("test", {{2, A::StencilTest}, {3, A::ColourWrite}}),
        pass("write again", {{2, A::StencilWrite}, {4, A::ColourWrite}}),
    };
    const FrameGraphPlan plan = compile_frame_graph(p, {false, true, true, true, true});
    using B = std::vector<std::pair<uint32_t, A>>;
    EXPECT_EQ(barriers(plan, 1), (B{{1, A::ColourWrite}}));
    EXPECT_EQ(barriers(plan, 2), (B{{2, A::StencilTest}, {3, A::ColourWrite}}));
    EXPECT_EQ(barriers(plan, 3), (B{{2, A::StencilWrite}, {4, A::ColourWrite}}));
    // What each barrier waits for: everything since the image's last barrier.
    EXPECT_EQ(plan.barriers[2][0].since, 1u << uint32_t(A::StencilWrite));
    EXPECT_EQ(plan.barriers[3][0].since, 1u << uint32_t(A::StencilTest));
}

TEST(FrameGraph, TheSinceMaskCoversEveryReadBetweenTwoBarriers) {
    const std::vector<FramePassDecl> p{
        pass("draw", {{1, A::ColourWrite}}),
        pass("read", {{1, A::Sampled}, {2, A::ColourWrite}}),
        pass("read", {{1, A::Sampled}, {3, A::ColourWrite}}),
        pass("clear", {{1, A::TransferWrite}}),
        pass("draw again", {{1, A::ColourWrite}}),
    };
    const FrameGraphPlan plan = compile_frame_graph(p, {false, true, true, true});
    ASSERT_EQ(plan.passes.size(), 5u);
    ASSERT_EQ(plan.barriers[3].size(), 1u);
    EXPECT_EQ(plan.barriers[3][0].last, A::Sampled);
    EXPECT_EQ(plan.barriers[3][0].since, 1u << uint32_t(A::Sampled));
    EXPECT_EQ(plan.final_access[1], A::ColourWrite);
}

TEST(FrameGraph, LifetimesAreTheFirstAndLastPassThatRunsAndUsesTheImage) {
    const std::vector<FramePassDecl> p{
        pass("dead", {{3, A::ColourWrite}}),
        pass("a", {{1, A::ColourWrite}}),
        pass("b", {{1, A::Sampled}, {2, A::ColourWrite}}),
        pass("c", {{2, A::Sampled}, {0, A::ColourWrite}}),
    };
    const FrameGraphPlan plan = compile_frame_graph(p, {true, false, false, false});
    ASSERT_EQ(plan.passes.size(), 3u);  // indices below count the passes that run
    EXPECT_EQ(plan.lifetimes[1].first, 0u);
    EXPECT_EQ(plan.lifetimes[1].last, 1u);
    EXPECT_EQ(plan.lifetimes[2].first, 1u);
    EXPECT_EQ(plan.lifetimes[2].last, 2u);
    EXPECT_EQ(plan.lifetimes[0].first, 2u);
}

// Slots per image from share_images, for images 0..n-1 (kNone shown as -1).
std::vector<int> slots_of(const SharedSlots& shared) {
    std::vector<int> out;
    for (uint32_t slot : shared.slot) out.push_back(slot == SharedSlots::kNone ? -1 : int(slot));
    return out;
}

TEST(FrameGraph, ImagesUsedAtDifferentTimesShareAndOverlappingOnesDoNot) {
    // A floor's pair (1, 2) ping-pongs into the composite (0); then the composite's partner (3)
    // ping-pongs with it; 4 is not shareable (an effect's own target).
    const std::vector<FramePassDecl> p{
        pass("floor tiles", {{1, A::ColourWrite}}),
        pass("clear partner", {{2, A::TransferWrite}}),
        pass("effect", {{1, A::Sampled}, {2, A::ColourWrite}}),
        pass("composite", {{2, A::Sampled}, {0, A::ColourWrite}}),
        pass("clear composite partner", {{3, A::TransferWrite}}),
        pass("global effect", {{0, A::Sampled}, {4, A::ColourWrite}}),
        pass("global effect 2", {{4, A::Sampled}, {3, A::ColourWrite}}),
        pass("output", {{3, A::Sampled}, {5, A::ColourWrite}}),
    };
    const std::vector<bool> read_after{false, false, false, false, true, true};
    const FrameGraphPlan plan = compile_frame_graph(p, read_after);
    const SharedSlots shared =
        share_images(plan, {false, true, true, true, false, false}, read_after);
    // 1 and 2 overlap (the effect reads one and writes the other); 3 starts after both end.
    EXPECT_EQ(slots_of(shared), (std::vector<int>{-1, 0, 1, 0, -1, -1}));
    EXPECT_EQ(shared.count, 2u);
}

TEST(FrameGraph, AnImageReadAfterTheFrameSharesWithNothingThatStartsLater) {
    // As a debug view keeps the floor's image (2) to the frame's end, the composite's partner
    // (3) cannot take its slot, and takes the floor's other image's (1).
    const std::vector<FramePassDecl> p{
        pass("floor tiles", {{1, A::ColourWrite}}),
        pass("effect", {{1, A::Sampled}, {2, A::ColourWrite}}),
        pass("composite", {{2, A::Sampled}, {0, A::ColourWrite}}),
        pass("global effect", {{0, A::Sampled}, {3, A::ColourWrite}}),
        pass("output", {{3, A::Sampled}, {2, A::Sampled}, {4, A::ColourWrite}}),
    };
    const std::vector<bool> read_after{false, false, true, false, true};
    const FrameGraphPlan plan = compile_frame_graph(p, read_after);
    const SharedSlots shared = share_images(plan, {false, true, true, true, false}, read_after);
    EXPECT_EQ(slots_of(shared), (std::vector<int>{-1, 0, 1, 0, -1}));
    EXPECT_EQ(shared.count, 2u);
    // Read after the frame, 1 keeps its slot to the end: 3 needs a slot of its own.
    const std::vector<bool> both_kept{false, true, true, false, true};
    const SharedSlots kept = share_images(compile_frame_graph(p, both_kept),
                                          {false, true, true, true, false}, both_kept);
    EXPECT_EQ(slots_of(kept), (std::vector<int>{-1, 0, 1, 2, -1}));
    EXPECT_EQ(kept.count, 3u);
}

TEST(FrameGraph, AnImageLastUsedByThePassThatFirstUsesAnotherDoesNotShareWithIt) {
    const std::vector<FramePassDecl> p{
        pass("a", {{1, A::ColourWrite}}),
        pass("a to b", {{1, A::Sampled}, {2, A::ColourWrite}}),
        pass("b to out", {{2, A::Sampled}, {0, A::ColourWrite}}),
        pass("dead", {{3, A::ColourWrite}}),
    };
    const std::vector<bool> read_after{true, false, false, false};
    const SharedSlots shared =
        share_images(compile_frame_graph(p, read_after), {false, true, true, true}, read_after);
    // 3 is written only by a culled pass: it needs no image at all.
    EXPECT_EQ(slots_of(shared), (std::vector<int>{-1, 0, 1, -1}));
}

}  // namespace
}  // namespace acetate
