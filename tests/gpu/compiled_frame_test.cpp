// The compiled frame (render/compiled_frame.hpp) on the device: a frame records one barrier
// command at most before each of its passes, whatever images the pass touches; a frame is
// compiled once per shape and run again, to the same bits, until the camera moves; the
// validation layer (on here, any message fails the test) sees every layout the passes use; the
// floor's and the composite's working images shared by when a frame uses them draw what one
// image per role draws.

#include "render_fixture.hpp"

namespace acetate::test {
namespace {

class CompiledFrames : public RenderTest {
  protected:
    // Floor 0 drawn straight into the accumulation, floors 1 and 2 through their target with
    // lighting (two passes' worth of ping-pong each), under a global bloom.
    SceneDesc three_floors() {
        SceneDesc scene = make_scene(96, 64, {0, 0, 0, 1});
        const uint32_t ground = add_floor(scene, "ground");
        add_tile(scene, ground, solid(96, 64, {0.1f, 0.2f, 0.3f, 1}), {0, 0, 96, 64});
        for (uint32_t f = 1; f <= 2; ++f) {
            const uint32_t floor = add_floor(scene, "lit " + std::to_string(f));
            add_tile(scene, floor, solid(30, 20, {0.5f, 0.4f, 0.3f, 0.75f}),
                     {10.0 + 30.0 * (f - 1), 10, 30, 20});
            scene.floors[floor].lights = {{{48, 32}, 60, {1, 0.9f, 0.8f}, 2.0f}};
            EffectRef lighting;
            lighting.plugin = "acetate.lighting";
            lighting.where = "floors[" + std::to_string(floor) + "].effects[0]";
            scene.floors[floor].effects = {lighting};
        }
        EffectRef bloom;
        bloom.plugin = "acetate.bloom";
        bloom.where = "global_effects[0]";
        scene.global_effects = {bloom};
        return scene;
    }
};

TEST_F(CompiledFrames, AFrameRecordsOneBarrierCommandAtMostPerPassThatRuns) {
    auto compositor = load(three_floors());
    ASSERT_TRUE(compositor);
    for (uint32_t floor = 0; floor < 3; ++floor) {
        SCOPED_TRACE("active floor " + std::to_string(floor));
        FrameStats stats;
        render(*compositor, floor, &stats);
        // Passes: the clear, floor 0's tiles, per lit floor its tiles, a clear, lighting and
        // the composite, bloom's passes and the output. Before the frame was compiled, every
        // pass recorded a full barrier per image it touched: about two per pass.
        EXPECT_GE(stats.frame_passes, 3u + 4 * floor);
        // One more: the frame's end, which makes every write visible to the host.
        EXPECT_LE(stats.barriers, uint64_t(stats.frame_passes) + 1);
        EXPECT_EQ(stats.frame_passes_culled, 0u);  // nothing here is written for nobody
    }
}

TEST_F(CompiledFrames, AFrameIsCompiledOnceAndRunsAgainToTheSameBitsUntilTheCameraMoves) {
    auto compositor = load(three_floors());
    ASSERT_TRUE(compositor);
    const uint64_t at_load = compositor->frames_compiled();
    EXPECT_EQ(at_load, 3u);  // one per active floor, in the view loaded with
    const ImageRGBA first = render(*compositor, 2);
    const ImageRGBA again = render(*compositor, 2);
    render(*compositor, 0);
    EXPECT_EQ(compositor->frames_compiled(), at_load);
    EXPECT_EQ(max_abs_difference(first, again), 0.0);

    compositor->set_view(OutputView::FloorRgb);  // another shape: compiled once
    render(*compositor, 2);
    render(*compositor, 2);
    EXPECT_EQ(compositor->frames_compiled(), at_load + 1);
    compositor->set_view(OutputView::Normal);
    EXPECT_EQ(max_abs_difference(first, render(*compositor, 2)), 0.0);
    EXPECT_EQ(compositor->frames_compiled(), at_load + 1);

    // A pan plans the floors again: the frames compiled for the old areas are dropped.
    ViewTransform pan = compositor->view_transform();
    pan.x += 8;
    ASSERT_TRUE(compositor->set_view_transform(pan));
    render(*compositor, 2);
    EXPECT_EQ(compositor->frames_compiled(), at_load + 2);
}

size_t transient_images(const Compositor& compositor) {
    size_t count = 0;
    for (const TargetInfo& t : compositor.targets_held())
        count += t.name.rfind("transient.", 0) == 0 ? 1 : 0;
    return count;
}

TEST_F(CompiledFrames, RolesUsedAtDifferentTimesShareImagesAndDrawTheSameBits) {
    // Floors with lighting (one effect: its result ends in the floor's ping-pong partner) under
    // a global bloom: three roles. In the debug views the floor's image is read to the frame's
    // end, beside the composite's partner; every view is loaded with its own pipelines.
    for (OutputView view : {OutputView::Normal, OutputView::FloorAlpha, OutputView::AccumAlpha,
                            OutputView::FloorRgb, OutputView::Violations, OutputView::Isolation}) {
        SCOPED_TRACE(std::string("view ") + to_string(view));
        CompositorOptions shared_options;
        shared_options.view = view;
        CompositorOptions apart_options = shared_options;
        apart_options.plan.share_targets = false;
        auto shared = load(three_floors(), shared_options);
        auto apart = load(three_floors(), apart_options);
        ASSERT_TRUE(shared && apart);
        EXPECT_EQ(transient_images(*shared), 2u);
        EXPECT_EQ(transient_images(*apart), 3u);
        for (uint32_t floor = 0; floor < 3; ++floor) {
            SCOPED_TRACE("active floor " + std::to_string(floor));
            EXPECT_EQ(max_abs_difference(render(*shared, floor), render(*apart, floor)), 0.0);
            auto composite = shared->read_accumulation();
            auto composite_apart = apart->read_accumulation();
            ASSERT_TRUE(composite && composite_apart);
            EXPECT_EQ(max_abs_difference(composite.value(), composite_apart.value()), 0.0);
            if (!view_reads_floor_target(view)) continue;
            auto own = shared->read_active_floor();
            auto own_apart = apart->read_active_floor();
            ASSERT_TRUE(own && own_apart);
            EXPECT_EQ(max_abs_difference(own.value(), own_apart.value()), 0.0);
        }
    }
}

}  // namespace
}  // namespace acetate::test
