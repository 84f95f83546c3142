// Hosts render every frame for as long as they run. Each shipped effect's quay scene (the
// scene it is validated on) is rendered for 1,000 frames in one process through the embedding
// API, time advancing as in a 60 Hz program, and must not grow the heap, the resident set or
// what the scene holds on the device. Validation layers on (ACETATE_VALIDATION=1 from ctest).
//
// What it guards: Mesa 22.3's lavapipe compiled a new variant of the water pass at every draw
// and kept it (1.8 MiB a frame) while the effect's values came from a uniform buffer
// (EffectPipelines::kFrameStorageBinding says why they no longer do).
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "acetate/host/host.hpp"
#include "api_host.hpp"

namespace acetate {
namespace {

constexpr uint32_t kWarmUpFrames = 60;
constexpr uint32_t kFrames = 1000;
// Measured over the 1,000 frames on lavapipe with the layers on: every shipped effect's heap
// changes by under 64 KiB (the validation layer's and malloc's own bookkeeping). 1 MiB over
// 1,000 frames is about 1 KiB a frame; the water leak this guards against was 1.8 MiB in one.
constexpr int64_t kHeapAllowance = 1 << 20;
// The resident set moves in whole pages and with malloc's arenas: 2 MiB leaves room for a few
// arena steps and still fails a leak of 2 KiB a frame.
constexpr int64_t kResidentAllowance = 2 << 20;

int64_t heap_in_use() {
    return int64_t(mallinfo2().uordblks);
}

int64_t resident_bytes() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6)) * 1024;
    return -1;
}

uint64_t bytes_held(const std::vector<host::ImageInfo>& images) {
    uint64_t sum = 0;
    for (const host::ImageInfo& i : images) sum += i.bytes;
    return sum;
}

class FrameMemory : public ::testing::TestWithParam<std::string> {};

TEST_P(FrameMemory, AThousandFramesDoNotGrowTheHostOrTheDevice) {
    const std::string id = GetParam();
    auto created = test::build_tree_host();
    ASSERT_TRUE(created) << created.error().message;
    auto scene = (*created)->load_scene_file(test::quay_scene(id));
    ASSERT_TRUE(scene) << scene.error().message;

    auto render_at = [&](uint32_t frame) -> bool {
        if (!(*scene)->set_time(frame / 60.0)) return false;
        auto stats = (*scene)->render();
        EXPECT_TRUE(stats) << stats.error().message;
        if (!stats) return false;
        EXPECT_EQ(stats->images_loaded + stats->targets_allocated + stats->shaders_compiled +
                      stats->pipelines_created,
                  0u)
            << "frame " << frame << " loaded, allocated or compiled";
        return stats->images_loaded + stats->targets_allocated + stats->shaders_compiled +
                   stats->pipelines_created ==
               0;
    };
    for (uint32_t f = 0; f < kWarmUpFrames; ++f) ASSERT_TRUE(render_at(f));

    const int64_t heap_before = heap_in_use();
    const int64_t resident_before = resident_bytes();
    const size_t images_before = (*scene)->images_held().size();
    const uint64_t bytes_before = bytes_held((*scene)->images_held());
    for (uint32_t f = kWarmUpFrames; f < kWarmUpFrames + kFrames; ++f) ASSERT_TRUE(render_at(f));
    const int64_t heap_growth = heap_in_use() - heap_before;
    const int64_t resident_growth = resident_bytes() - resident_before;

    EXPECT_LE(heap_growth, kHeapAllowance)
        << id << ": the heap grew by " << heap_growth / 1024 << " KiB over " << kFrames
        << " frames (" << heap_growth / kFrames << " bytes a frame)";
    EXPECT_LE(resident_growth, kResidentAllowance)
        << id << ": the resident set grew by " << resident_growth / 1024 << " KiB over " << kFrames
        << " frames";
    EXPECT_EQ((*scene)->images_held().size(), images_before) << id << ": device images held";
    EXPECT_EQ(bytes_held((*scene)->images_held()), bytes_before) << id << ": device bytes held";
    EXPECT_EQ((*created)->validation_messages(), 0u);
    std::printf("%s: heap %+lld KiB, resident %+lld KiB over %u frames\n", id.c_str(),
                static_cast<long long>(heap_growth / 1024),
                static_cast<long long>(resident_growth / 1024), kFrames);
}

INSTANTIATE_TEST_SUITE_P(EveryShippedEffect, FrameMemory,
                         ::testing::Values("acetate.lighting", "acetate.water", "acetate.specular",
                                           "acetate.fire", "acetate.bloom"),
                         [](const auto& info) {
                             std::string name = info.param.substr(info.param.find('.') + 1);
                             return name;
                         });

}  // namespace
}  // namespace acetate
