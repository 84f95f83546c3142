// Per-step GPU times through the embedding API (SceneOptions::gpu_timings): each frame of a
// scene with an effect names every step it timed, the effect's passes among them, each time
// finite and non-negative and together no more than the frame's own wall time; timing costs
// no load, allocation or compile in a frame and changes no pixel; without it, nothing is
// timed. Validation layers on (ACETATE_VALIDATION=1 from ctest).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "acetate/host/host.hpp"
#include "api_host.hpp"

namespace acetate {
namespace {

TEST(GpuTimings, EveryStepOfAFrameIsTimedWhenAskedAndNothingElseChanges) {
    auto created = test::build_tree_host();
    ASSERT_TRUE(created) << created.error().message;
    host::Host& host = **created;
    host::SceneOptions timed_options;
    timed_options.gpu_timings = true;
    auto timed = host.load_scene_file(test::quay_scene("acetate.lighting"), timed_options);
    ASSERT_TRUE(timed) << timed.error().message;
    auto plain = host.load_scene_file(test::quay_scene("acetate.lighting"));
    ASSERT_TRUE(plain) << plain.error().message;
    ASSERT_EQ((*timed)->gpu_timings_warning(), "") << "lavapipe's queue has timestamps";
    EXPECT_EQ((*plain)->gpu_timings_warning(), "");

    for (int frame = 0; frame < 3; ++frame) {
        ASSERT_TRUE((*timed)->set_time(0.5 * frame));
        ASSERT_TRUE((*plain)->set_time(0.5 * frame));
        auto stats = (*timed)->render();
        ASSERT_TRUE(stats) << stats.error().message;
        auto untimed = (*plain)->render();
        ASSERT_TRUE(untimed) << untimed.error().message;
        EXPECT_TRUE(untimed->gpu_passes.empty());

        ASSERT_FALSE(stats->gpu_passes.empty());
        double sum = 0;
        for (const host::PassTime& pass : stats->gpu_passes) {
            EXPECT_FALSE(pass.name.empty());
            EXPECT_TRUE(std::isfinite(pass.milliseconds) && pass.milliseconds >= 0)
                << pass.name << ": " << pass.milliseconds;
            sum += pass.milliseconds;
        }
        // The steps run one after another inside the frame's one submission, which the frame's
        // wall time (record, submit, wait) contains.
        EXPECT_LE(sum, stats->milliseconds) << "GPU steps summed past the frame's wall time";
        const auto names_effect = [](const host::PassTime& pass) {
            return pass.name.find("acetate.lighting") != std::string::npos;
        };
        EXPECT_TRUE(std::any_of(stats->gpu_passes.begin(), stats->gpu_passes.end(), names_effect))
            << "no timed pass of the scene's effect; the first: " << stats->gpu_passes[0].name;
        if (frame > 0) {
            EXPECT_EQ(stats->images_loaded + stats->targets_allocated + stats->shaders_compiled +
                          stats->pipelines_created,
                      0u)
                << "a timed frame loaded, allocated or compiled something";
        }
        auto a = (*timed)->read_frame();
        auto b = (*plain)->read_frame();
        ASSERT_TRUE(a && b);
        EXPECT_EQ(a->rgba, b->rgba) << "timing changed the frame";
    }
}

}  // namespace
}  // namespace acetate
