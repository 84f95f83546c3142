// The camera (Scene::set_camera, ABI 1.2) through the embedding API, with the shipped plugins:
// a region at scale 1 is the same region of the whole frame, bit for bit where an effect reads
// only its own pixel and away from the region's edge by the distance an effect reads around a
// pixel; a pan at one scale builds, loads, allocates and compiles nothing, in the change and in
// the frame; another scale runs build() again and its next pan costs nothing either; a render at
// scale 1/2 is the whole frame averaged over 2x2 pixels within a stated tolerance; bad cameras
// are refused with a line naming the number. Validation layers on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "acetate/host/host.hpp"
#include "api_host.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

fs::path harbour_scene() {
    return fs::path(ACETATE_SOURCE_DIR) / "examples" / "harbour" / "scene.json";
}

// Pixels of `region` (the camera's output, origin at whole-frame pixel (x, y)) that differ from
// the whole frame, counting only those at least `margin` pixels inside the region's edges.
struct Difference {
    uint64_t compared = 0, differing = 0;
    float largest = 0;
};
Difference compare_region(const host::Image& whole, const host::Image& region, uint32_t x,
                          uint32_t y, uint32_t margin) {
    Difference d;
    for (uint32_t j = margin; j + margin < region.height; ++j)
        for (uint32_t i = margin; i + margin < region.width; ++i) {
            ++d.compared;
            bool differs = false;
            for (uint32_t c = 0; c < 4; ++c) {
                const float a = region.rgba[(size_t(j) * region.width + i) * 4 + c];
                const float b = whole.rgba[(size_t(j + y) * whole.width + i + x) * 4 + c];
                differs |= a != b;
                d.largest = std::max(d.largest, std::abs(a - b));
            }
            d.differing += differs;
        }
    return d;
}

class Camera : public ::testing::Test {
  protected:
    void SetUp() override {
        auto created = test::build_tree_host();
        ASSERT_TRUE(created) << created.error().message;
        host_ = std::move(created.value());
    }

    std::unique_ptr<host::Scene> load(const fs::path& file) {
        auto scene = host_->load_scene_file(file);
        EXPECT_TRUE(scene) << scene.error().message;
        return scene ? std::move(scene.value()) : nullptr;
    }

    static host::Image frame(host::Scene& scene, double time, host::FrameStatistics* stats = {}) {
        EXPECT_TRUE(scene.set_time(time));
        auto rendered = scene.render();
        EXPECT_TRUE(rendered) << rendered.error().message;
        if (rendered && stats) *stats = rendered.value();
        auto image = scene.read_frame();
        EXPECT_TRUE(image) << image.error().message;
        return image ? image.value() : host::Image{};
    }

    // The scene's whole frame at `time` against its frame through a camera at scale 1 whose
    // region starts at whole pixel (x, y) and is w x h: the Difference `margin` pixels in.
    Difference region_against_whole(const fs::path& file, uint32_t x, uint32_t y, uint32_t w,
                                    uint32_t h, uint32_t margin);

    std::unique_ptr<host::Host> host_;
};

Difference Camera::region_against_whole(const fs::path& file, uint32_t x, uint32_t y, uint32_t w,
                                        uint32_t h, uint32_t margin) {
    auto scene = load(file);
    if (!scene) return {};
    const host::Image whole = frame(*scene, 1.25);
    auto moved = scene->set_camera({double(x), double(y), double(w), double(h), 1});
    EXPECT_TRUE(moved) << moved.error().message;
    const host::Image region = frame(*scene, 1.25);
    EXPECT_EQ(region.width, w);
    EXPECT_EQ(region.height, h);
    return compare_region(whole, region, x, y, margin);
}

bool costs_nothing(const host::CameraChange& c) {
    return c.images_loaded == 0 && c.targets_allocated == 0 && c.shaders_compiled == 0 &&
           c.pipelines_created == 0;
}
bool costs_nothing(const host::FrameStatistics& s) {
    return s.images_loaded == 0 && s.targets_allocated == 0 && s.shaders_compiled == 0 &&
           s.pipelines_created == 0;
}

// Effects that read only their own pixel (and scene-space textures at its scene position): the
// region is the whole frame's, exactly. Water reads the bed around a pixel (refraction), so it
// is exact only where every tap lies inside the region: an offset of at most `refraction` (3
// scene pixels by default) times the waves (1) along a slope of length 1, the tap disk's spread
// of half that, and a bilinear texel: 6 pixels. The margin of 32 holds that with room (and the
// harbour's water, at the same defaults, below).
struct RegionCase {
    const char* plugin;
    uint32_t margin;
};
class CameraRegion : public Camera, public ::testing::WithParamInterface<RegionCase> {};

TEST_P(CameraRegion, IsTheSameRegionOfTheWholeFrame) {
    auto scene = load(test::quay_scene(GetParam().plugin));
    ASSERT_TRUE(scene);
    const host::Image whole = frame(*scene, 2.5);
    // The quay scenes are 400 x 192: a region off every edge, the lights partly outside it.
    auto change = scene->set_camera({96, 40, 224, 120, 1});
    ASSERT_TRUE(change) << change.error().message;
    const host::Image region = frame(*scene, 2.5);
    ASSERT_EQ(region.width, 224u);
    ASSERT_EQ(region.height, 120u);
    const Difference d = compare_region(whole, region, 96, 40, GetParam().margin);
    EXPECT_GT(d.compared, 8000u);
    EXPECT_EQ(d.differing, 0u) << "largest difference " << d.largest;
}

INSTANTIATE_TEST_SUITE_P(ShippedPlugins, CameraRegion,
                         ::testing::Values(RegionCase{"acetate.lighting", 0},
                                           RegionCase{"acetate.specular", 0},
                                           RegionCase{"acetate.fire", 0},
                                           RegionCase{"acetate.water", 32}),
                         [](const auto& info) {
                             std::string name = info.param.plugin;
                             return name.substr(name.find('.') + 1);
                         });

// The harbour: five floors of scaled and fractional tiles, every shipped floor effect (water
// reading up to its refraction's reach around a pixel), bloom on the composite. Its floors
// under a camera are the whole frame's, bit for bit, from 32 pixels inside the region's edge.
TEST_F(Camera, HarbourFloorsInARegionAreTheWholeFramesBitForBit) {
    const fs::path floors_only = test::write_edited_scene(
        harbour_scene(), [](nlohmann::json& scene) { scene.erase("global_effects"); },
        test::scratch_dir() / "harbour-floors.json");
    const Difference d = region_against_whole(floors_only, 257, 131, 768, 448, 32);
    EXPECT_GT(d.compared, 250000u);
    EXPECT_EQ(d.differing, 0u) << "largest difference " << d.largest;
}

// Bloom ("high": levels 1 to 6) halves the frame six times; a region whose origin is a multiple
// of 64 cuts the same texels at every level, and from 128 pixels inside its edge (the tent's
// taps level after level) it reads what the whole frame's chain reads. Not bit for bit: its
// passes sample with normalised coordinates, which round differently for a level 384 texels
// wide than for one 640 wide, and lavapipe's bilinear weights are 8-bit (a step of 1/256 of
// the difference between two texels): the measured difference is 1/1024, bounded at 1/256.
TEST_F(Camera, HarbourRegionWithBloomMatchesAwayFromItsEdge) {
    const Difference d = region_against_whole(harbour_scene(), 256, 128, 768, 448, 128);
    EXPECT_GT(d.compared, 90000u);
    EXPECT_LE(d.largest, 1.0f / 256);
}

TEST_F(Camera, APanAtOneScaleBuildsLoadsAllocatesAndCompilesNothing) {
    auto scene = load(harbour_scene());
    ASSERT_TRUE(scene);
    for (double scale : {1.0, 0.5}) {
        SCOPED_TRACE("scale " + std::to_string(scale));
        // A window of 640 x 360 over the harbour (1280 x 720).
        const double w = 640 / scale, h = 360 / scale;
        auto first = scene->set_camera({0, 0, w, h, scale});
        ASSERT_TRUE(first) << first.error().message;
        EXPECT_TRUE(first->rebuilt);
        frame(*scene, 0);  // the first frame at this scale
        for (int step = 1; step <= 6; ++step) {
            auto moved = scene->set_camera({17.0 * step, 9.5 * step, w, h, scale});
            ASSERT_TRUE(moved) << moved.error().message;
            EXPECT_FALSE(moved->rebuilt);
            EXPECT_FALSE(moved->resized);
            EXPECT_TRUE(costs_nothing(moved.value())) << "step " << step;
            host::FrameStatistics stats;
            const host::Image image = frame(*scene, step / 10.0, &stats);
            EXPECT_EQ(image.width, 640u);
            EXPECT_EQ(image.height, 360u);
            EXPECT_TRUE(costs_nothing(stats)) << "step " << step;
        }
    }
    EXPECT_EQ(host_->validation_messages(), 0u);
}

// At scale 1/2 each output pixel's centre is the corner shared by 2 x 2 scene pixels: a tile
// filtered there is their average, and an effect evaluated there differs from the average of
// its four values by its curvature over a pixel. Lighting's falloff is smooth (radius 180 on
// the quay), so the 2 x 2 average of the whole frame matches within 1/256 per channel: about
// one 8-bit step, where an effect that ignored the scale misplaces its light by half the
// scene and misses by far more.
TEST_F(Camera, HalfScaleIsTheWholeFrameAveragedOverTwoByTwoPixels) {
    auto scene = load(test::quay_scene("acetate.lighting"));
    ASSERT_TRUE(scene);
    const host::Image whole = frame(*scene, 0);
    ASSERT_TRUE(scene->set_camera({0, 0, 400, 192, 0.5}));
    const host::Image half = frame(*scene, 0);
    ASSERT_EQ(half.width, 200u);
    ASSERT_EQ(half.height, 96u);
    float largest = 0;
    for (uint32_t j = 0; j < half.height; ++j)
        for (uint32_t i = 0; i < half.width; ++i)
            for (uint32_t c = 0; c < 4; ++c) {
                float sum = 0;
                for (uint32_t k = 0; k < 4; ++k)
                    sum +=
                        whole.rgba[(size_t(2 * j + k / 2) * whole.width + 2 * i + k % 2) * 4 + c];
                largest = std::max(
                    largest, std::abs(half.rgba[(size_t(j) * half.width + i) * 4 + c] - sum / 4));
            }
    EXPECT_LT(largest, 1.0f / 256);
}

TEST_F(Camera, AResizeAllocatesAndTheNextFrameIsStillTheRegion) {
    auto scene = load(test::quay_scene("acetate.fire"));
    ASSERT_TRUE(scene);
    const host::Image whole = frame(*scene, 1.0);
    ASSERT_TRUE(scene->set_camera({50, 20, 200, 100, 1}));
    frame(*scene, 1.0);
    auto resized = scene->set_camera({50, 20, 300, 150, 1});
    ASSERT_TRUE(resized) << resized.error().message;
    EXPECT_TRUE(resized->resized);
    EXPECT_GT(resized->targets_allocated, 0u);
    EXPECT_EQ(resized->shaders_compiled, 0u);  // every pipeline from the pool
    const host::Image region = frame(*scene, 1.0);
    ASSERT_EQ(region.width, 300u);
    EXPECT_EQ(compare_region(whole, region, 50, 20, 0).differing, 0u);
    // Back to the whole canvas: the frame is the one before any camera, bit for bit.
    ASSERT_TRUE(scene->set_camera({0, 0, 400, 192, 1}));
    EXPECT_EQ(frame(*scene, 1.0).rgba, whole.rgba);
}

TEST_F(Camera, BadCamerasAreRefusedNamingTheNumberAndChangeNothing) {
    auto scene = load(test::quay_scene("acetate.lighting"));
    ASSERT_TRUE(scene);
    const host::Image before = frame(*scene, 0);
    const double nan = std::nan("");
    const std::vector<std::pair<host::Camera, std::string>> bad = {
        {{0, 0, 100, 100, 0}, "camera: scale 0"},
        {{0, 0, 100, 100, 65}, "camera: scale 65"},
        {{0, 0, 100, 100, nan}, "camera: scale nan"},
        {{nan, 0, 100, 100, 1}, "camera: origin (nan, 0)"},
        {{0, 1e9, 100, 100, 1}, "camera: origin (0, 1000000000)"},
        {{0, 0, 0, 100, 1}, "camera: size 0 x 100"},
        {{0, 0, 100, -3, 1}, "camera: size 100 x -3"},
        {{0, 0, 0.2, 100, 1}, "camera: an output of 0 x 100 pixels"},
        {{0, 0, 5000, 100, 64}, "camera: an output of 320000 x 6400 pixels"},
    };
    for (const auto& [camera, expected] : bad) {
        auto refused = scene->set_camera(camera);
        ASSERT_FALSE(refused) << expected;
        EXPECT_NE(refused.error().message.find(expected), std::string::npos)
            << refused.error().message;
        EXPECT_NE(refused.error().message.find("quay.json"), std::string::npos);
    }
    EXPECT_EQ(scene->camera().width, 400);
    EXPECT_EQ(frame(*scene, 0).rgba, before.rgba);
}

}  // namespace
}  // namespace acetate
