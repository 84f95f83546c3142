// One Host used from several threads, as an interactive program does (a render thread, a
// loading thread): two scenes rendered at once from two threads, and loads beside frames. Each
// thread's frames must be bit for bit what the same calls give on one thread, and nothing may
// crash or report a validation message. Validation layers on.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "acetate/host/host.hpp"
#include "api_host.hpp"

namespace acetate {
namespace {

std::unique_ptr<host::Host> make_host() {
    auto created = test::build_tree_host();
    EXPECT_TRUE(created) << created.error().message;
    return created ? std::move(created.value()) : nullptr;
}

// The frame at `time`, or empty with the failure recorded in `error`.
std::vector<float> frame_at(host::Scene& scene, double time, std::string& error) {
    if (auto set = scene.set_time(time); !set) {
        error = set.error().message;
        return {};
    }
    if (auto stats = scene.render(); !stats) {
        error = stats.error().message;
        return {};
    }
    auto frame = scene.read_frame();
    if (!frame) {
        error = frame.error().message;
        return {};
    }
    return std::move(frame->rgba);
}

constexpr int kFrames = 24;

// What one thread renders: kFrames frames of `scene` at times k / 10, compared as it goes with
// `expected` (the same frames rendered first on one thread). Counts mismatches.
void render_and_compare(host::Scene& scene, const std::vector<std::vector<float>>& expected,
                        std::atomic<int>& mismatches, std::string& error) {
    for (int k = 0; k < kFrames; ++k)
        if (frame_at(scene, k / 10.0, error) != expected[size_t(k)]) ++mismatches;
}

std::vector<std::vector<float>> frames_on_one_thread(host::Scene& scene) {
    std::vector<std::vector<float>> out;
    std::string error;
    for (int k = 0; k < kFrames; ++k) {
        out.push_back(frame_at(scene, k / 10.0, error));
        EXPECT_EQ(error, "");
    }
    return out;
}

TEST(HostThreads, TwoScenesOfOneHostRenderFromTwoThreadsAsOnOne) {
    auto host = make_host();
    ASSERT_TRUE(host);
    auto fire = host->load_scene_file(test::quay_scene("acetate.fire"));
    auto water = host->load_scene_file(test::quay_scene("acetate.water"));
    ASSERT_TRUE(fire) << fire.error().message;
    ASSERT_TRUE(water) << water.error().message;
    const auto fire_frames = frames_on_one_thread(**fire);
    const auto water_frames = frames_on_one_thread(**water);

    std::atomic<int> mismatches{0};
    std::string fire_error, water_error;
    std::thread a([&] { render_and_compare(**fire, fire_frames, mismatches, fire_error); });
    std::thread b([&] { render_and_compare(**water, water_frames, mismatches, water_error); });
    a.join();
    b.join();
    EXPECT_EQ(fire_error, "");
    EXPECT_EQ(water_error, "");
    EXPECT_EQ(mismatches.load(), 0) << "frames that differ from the one-thread run";
    EXPECT_EQ(host->validation_messages(), 0u);
}

TEST(HostThreads, LoadsOnOneThreadBesideFramesOnAnother) {
    auto host = make_host();
    ASSERT_TRUE(host);
    auto fire = host->load_scene_file(test::quay_scene("acetate.fire"));
    ASSERT_TRUE(fire) << fire.error().message;
    const auto fire_frames = frames_on_one_thread(**fire);
    std::vector<float> bloom_frame;
    {
        auto bloom = host->load_scene_file(test::quay_scene("acetate.bloom"));
        ASSERT_TRUE(bloom) << bloom.error().message;
        std::string error;
        bloom_frame = frame_at(**bloom, 0.5, error);
        ASSERT_EQ(error, "");
    }

    std::atomic<int> mismatches{0};
    std::string render_error, load_error;
    std::thread renderer(
        [&] { render_and_compare(**fire, fire_frames, mismatches, render_error); });
    std::thread loader([&] {
        // Loads, a frame and the scene's destruction, again and again beside the frames.
        for (int i = 0; i < 4; ++i) {
            auto bloom = host->load_scene_file(test::quay_scene("acetate.bloom"));
            if (!bloom) {
                load_error = bloom.error().message;
                return;
            }
            if (frame_at(**bloom, 0.5, load_error) != bloom_frame) ++mismatches;
        }
    });
    renderer.join();
    loader.join();
    EXPECT_EQ(render_error, "");
    EXPECT_EQ(load_error, "");
    EXPECT_EQ(mismatches.load(), 0);
    EXPECT_EQ(host->validation_messages(), 0u);
}

}  // namespace
}  // namespace acetate
