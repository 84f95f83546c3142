// acetate.fire against a CPU replica of its particles (tests/support/fire_model.hpp): every
// particle is where the replica says at times 0, 0.37, 1.9 and 10^5 s, and every pixel outside all
// of them is the input, bit for bit. Then the contract where the fire leaves its tile, a mask on a
// tile that is offset and scaled, four floors each with its own fire, odd canvases, an empty mask.

#include <Imath/half.h>
#include <fmt/format.h>

#include <cmath>
#include <cstring>

#include "fire_model.hpp"
#include "render_fixture.hpp"
#include "test_files.hpp"

namespace acetate::test {
namespace {

namespace model = fire_model;

float half_of(float v) {
    return float(Imath::half(v));
}

// The default counts per emitter (smoke, flames, embers) and the emitter spacing; no glow, so
// only particles change pixels.
const std::array<int, 3> kCounts{1, 5, 2};
nlohmann::json test_params() {
    return {{"glow", 0.0}, {"wind", {10.0, -3.0}}, {"seed", 7}, {"smoke", 0.5}};
}
model::Params test_model() {
    model::Params p;
    p.wind = {10, -3};
    p.seed = 7;
    return p;
}

class FireTest : public RenderTest {
  protected:
    // A floor with `tile` at `rect` carrying `fire` (same size as the tile) as its fire mask.
    uint32_t fire_floor(SceneDesc& scene, const ImageRGBA& tile, const ImageRGBA& fire,
                        SceneRect rect, const nlohmann::json& params) {
        const uint32_t floor = add_floor(scene, fmt::format("f{}", scene.floors.size()));
        add_tile(scene, floor, tile, rect);
        scene.floors[floor].tiles.back().masks["fire"] =
            write_exr(dir() / fmt::format("fire{}.exr", masks_++), fire);
        if (!params.is_null()) {
            EffectRef ref;
            ref.plugin = "acetate.fire";
            ref.params = params;
            ref.where = fmt::format("floors[{}].effects[0]", floor);
            scene.floors[floor].effects.push_back(ref);
        }
        return floor;
    }

    ImageRGBA floor_after_effects(Compositor& compositor, uint32_t floor, double time,
                                  FrameStats* stats = nullptr) {
        compositor.set_view(OutputView::FloorRgb);
        auto frame = compositor.render(floor, time);
        EXPECT_TRUE(frame.ok()) << (frame.ok() ? "" : frame.error().message);
        if (frame.ok() && stats) *stats = frame.value();
        auto image = compositor.read_active_floor();
        EXPECT_TRUE(image.ok());
        return image.ok() ? std::move(image.value()) : ImageRGBA{};
    }

  private:
    int masks_ = 0;  // every mask gets its own file, whatever scene and floor it is for
};

// A mask: 1 in the block [x0, x1) x [y0, y1) (as a one-channel file reads: grey, alpha 1).
ImageRGBA block_mask(uint32_t width, uint32_t height, int x0, int y0, int x1, int y1) {
    ImageRGBA mask(width, height);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            float* p = mask.at(x, y);
            const bool in = int(x) >= x0 && int(x) < x1 && int(y) >= y0 && int(y) < y1;
            p[0] = p[1] = p[2] = in ? 1.0f : 0.0f;
            p[3] = 1.0f;
        }
    return mask;
}

// The alpha of the bottom part of the canvas: opaque ground from row 40 down, transparent above.
ImageRGBA ground(uint32_t width, uint32_t height) {
    ImageRGBA tile(width, height);
    for (uint32_t y = 40; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            float* p = tile.at(x, y);
            p[0] = 0.3f, p[1] = 0.25f, p[2] = 0.2f, p[3] = 1.0f;
        }
    return tile;
}

TEST_F(FireTest, EveryParticleIsWhereTheReplicaSaysAndNothingElseChanges) {
    constexpr uint32_t kW = 112, kH = 96;
    SceneDesc scene = make_scene(kW, kH);
    const ImageRGBA tile = ground(kW, kH);
    // One emitter: the 6x6 cell (8, 8) of the default spacing, fully alight, at the ground's
    // top edge, so particles rise into the transparent sky.
    const uint32_t floor =
        fire_floor(scene, tile, block_mask(kW, kH, 48, 42, 54, 48), {0, 0, kW, kH}, test_params());
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    // The cell [48, 54) x [42, 48) is cell (8, 7): its centre (51, 45), strength 1, emitter 0.
    const model::Emitter emitter{51, 45, 1, 1, 0};
    // Around the 2048 s clock's wrap too: nothing may jump there.
    for (double time : {0.0, 0.37, 1.9, 1e5, 2047.999, 2048.001}) {
        const std::string what = fmt::format("t = {}", time);
        const ImageRGBA out = floor_after_effects(*compositor, floor, time);
        ASSERT_EQ(out.width, kW) << what;
        const auto particles = model::particles_at(time, emitter, kCounts, test_model());
        // Outside every particle's disc (half a pixel to spare for float positions): the input.
        int outside = 0, changed = 0;
        for (uint32_t y = 0; y < kH; ++y)
            for (uint32_t x = 0; x < kW; ++x) {
                bool near = false;
                for (const auto& p : particles)
                    near |= std::hypot(x + 0.5 - p.x, y + 0.5 - p.y) < p.radius + 0.5;
                const float* o = out.at(x, y);
                const float* in = tile.at(x, y);
                bool same = true;
                for (int c = 0; c < 4; ++c) same &= o[c] == half_of(in[c]);
                changed += !same;
                if (near) continue;
                ++outside;
                ASSERT_TRUE(same) << what << ": pixel " << x << "," << y
                                  << " changed, far from every particle";
            }
        EXPECT_GT(outside, int(kW * kH) / 2) << what;
        EXPECT_GT(changed, 10) << what << ": the fire is alight";
        // Every particle well into its life shows at its centre.
        int seen = 0;
        for (const auto& p : particles) {
            const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
            if (p.envelope < 0.5 || x < 0 || y < 0 || x >= int(kW) || y >= int(kH)) continue;
            const float* o = out.at(x, y);
            const float* in = tile.at(x, y);
            bool same = true;
            for (int c = 0; c < 4; ++c) same &= o[c] == half_of(in[c]);
            EXPECT_FALSE(same) << what << ": particle of kind " << p.kind << " at " << p.x << ","
                               << p.y << " is not drawn there";
            ++seen;
        }
        EXPECT_GE(seen, 3) << what;
    }
}

// The replica itself: across the clock's wrap every particle that is mid-life moves by well
// under a pixel in 2 ms (a jump there would be a new life's draws).
TEST(FireModel, NothingJumpsWhereTheClockWraps) {
    const model::Emitter emitter{51, 45, 1, 1, 0};
    for (uint32_t seed : {1u, 7u, 12345u}) {
        model::Params p = test_model();
        p.seed = seed;
        const auto before = model::particles_at(2047.999, emitter, {2, 8, 3}, p);
        const auto after = model::particles_at(2048.001, emitter, {2, 8, 3}, p);
        for (size_t i = 0; i < before.size(); ++i) {
            if (before[i].envelope <= 0.01 || after[i].envelope <= 0.01) continue;  // born or died
            EXPECT_LT(std::hypot(before[i].x - after[i].x, before[i].y - after[i].y), 0.5)
                << "seed " << seed << " particle " << i;
        }
    }
}

// A small tile with fast embers, smoke and a strong wind against it: the particles reach far
// past the tile, and the declared reach must hold all of them (the same pixels as a render
// that shades the whole canvas).
TEST_F(FireTest, TheDeclaredReachHoldsEveryParticle) {
    // Embers arc up to 190 px and 120 px aside, smoke drifts 190 px left: a reach of about 230
    // px, less than the canvas to the tile's left.
    constexpr uint32_t kW = 600, kH = 400;
    constexpr int kX = 450, kY = 300;
    SceneDesc scene = make_scene(kW, kH);
    nlohmann::json params = test_params();
    params.update({{"ember_speed", 150.0},
                   {"embers", 2.0},
                   {"smoke", 0.8},
                   {"smoke_height", 60.0},
                   {"wind", {-40.0, 10.0}},
                   {"glow", 1.0}});
    const uint32_t floor = fire_floor(scene, solid(24, 8, {0.3f, 0.3f, 0.3f, 1}),
                                      block_mask(24, 8, 4, 0, 20, 8), {kX, kY, 24, 8}, params);
    CompositorOptions whole;
    whole.ignore_declared_reach = true;
    auto declared = load(scene), everywhere = load(scene, whole);
    ASSERT_TRUE(declared && everywhere);
    for (double time : {0.0, 0.37, 1.9, 1e5}) {
        FrameStats a_stats, b_stats;
        const ImageRGBA a = floor_after_effects(*declared, floor, time, &a_stats);
        const ImageRGBA b = floor_after_effects(*everywhere, floor, time, &b_stats);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0)
            << "t = " << time;
        EXPECT_LT(a_stats.pixels_shaded, b_stats.pixels_shaded) << "the reach saves pixels";
        int outside = 0;  // particles really do leave the tile
        for (uint32_t y = 0; y < kH; ++y)
            for (uint32_t x = 0; x < kW; ++x)
                outside += (x < kX || x >= kX + 24 || y < kY || y >= kY + 8) && a.at(x, y)[3] > 0;
        EXPECT_GT(outside, 20) << "t = " << time;
    }
}

TEST_F(FireTest, FireAboveItsTileKeepsTheContractAndNeverLowersAlpha) {
    constexpr uint32_t kW = 80, kH = 72;
    SceneDesc scene = make_scene(kW, kH);
    const ImageRGBA tile = ground(kW, kH);
    nlohmann::json params = test_params();
    params.update({{"glow", 1.0}, {"embers", 4.0}, {"intensity", 64.0}});
    const uint32_t floor =
        fire_floor(scene, tile, block_mask(kW, kH, 10, 40, 70, 46), {0, 0, kW, kH}, params);
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    for (double time : {0.0, 0.37, 1.9, 1e5}) {
        FrameStats stats;
        const ImageRGBA out = floor_after_effects(*compositor, floor, time, &stats);
        ASSERT_EQ(out.width, kW);
        EXPECT_EQ(stats.violations, 0u);
        int above = 0;
        for (uint32_t y = 0; y < kH; ++y)
            for (uint32_t x = 0; x < kW; ++x) {
                const float* o = out.at(x, y);
                ASSERT_GE(o[3], half_of(tile.at(x, y)[3])) << "alpha lowered at " << x << "," << y;
                ASSERT_LE(o[3], 1.0f);
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(o[c]) && o[c] >= 0.0f) << x << "," << y;
                    if (o[3] == 0.0f) {
                        ASSERT_EQ(o[c], 0.0f) << "colour at alpha 0, " << x << "," << y;
                    }
                }
                above += y < 40 && o[3] > 0.0f;
            }
        EXPECT_GT(above, 20) << "t = " << time << ": the fire rises above its tile";
    }
}

TEST_F(FireTest, AMaskOnAnOffsetScaledTileBurnsAtItsScenePixels) {
    constexpr uint32_t kW = 96, kH = 96;
    SceneDesc scene = make_scene(kW, kH);
    // A 20x16 tile drawn at (30.5, 50.25), twice its size; its mask is alight in the 3x3 block at
    // tile pixels (12..14, 3..5), which lands on scene pixels x 54.5..60.5, y 56.25..62.25.
    const ImageRGBA tile = solid(20, 16, {0.2f, 0.2f, 0.2f, 1});
    nlohmann::json params = test_params();
    params.update({{"wind", {0.0, 0.0}}, {"smoke", 0.0}, {"embers", 0.0}});
    const uint32_t floor =
        fire_floor(scene, tile, block_mask(20, 16, 12, 3, 15, 6), {30.5, 50.25, 40, 32}, params);
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    // Flames start within a cell (6 px) of the lit pixels, rise at most flame_height and reach
    // a flame_size radius: that is where pixels may change, and nowhere else.
    const double x0 = 54.5 - 6 - 5 * 0.3 - 5 - 1, x1 = 60.5 + 6 + 5 * 0.3 + 5 + 1;
    const double y0 = 56.25 - 6 - 26 - 5 - 1, y1 = 62.25 + 6 + 5 + 1;
    int changed = 0, above = 0;
    const ImageRGBA bare = [&] {
        compositor->set_effects_enabled(false);
        ImageRGBA image = floor_after_effects(*compositor, floor, 1.9);
        compositor->set_effects_enabled(true);
        return image;
    }();
    const ImageRGBA out = floor_after_effects(*compositor, floor, 1.9);
    ASSERT_EQ(out.width, kW);
    for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
            if (std::memcmp(out.at(x, y), bare.at(x, y), 4 * sizeof(float)) == 0) continue;
            ++changed;
            above += y + 0.5 < 56.25;
            ASSERT_TRUE(x + 0.5 > x0 && x + 0.5 < x1 && y + 0.5 > y0 && y + 0.5 < y1)
                << "fire at " << x << "," << y << ", away from the mask's scene pixels";
        }
    EXPECT_GT(changed, 10);
    EXPECT_GT(above, 5) << "flames rise above the lit pixels";
}

TEST_F(FireTest, FourFloorsEachKeepTheirOwnFireAndASwitchRestartsNothing) {
    constexpr uint32_t kW = 64, kH = 64;
    const ImageRGBA tile = ground(kW, kH);
    SceneDesc stacked = make_scene(kW, kH);
    std::vector<SceneDesc> alone;
    for (int f = 0; f < 4; ++f) {
        const ImageRGBA fire = block_mask(kW, kH, 6 + 12 * f, 40, 18 + 12 * f, 46);
        nlohmann::json params = test_params();
        params["seed"] = 10 + f;
        fire_floor(stacked, tile, fire, {0, 0, kW, kH}, params);
        alone.push_back(make_scene(kW, kH));
        alone.back().file = dir() / fmt::format("alone{}.json", f);
        fire_floor(alone.back(), tile, fire, {0, 0, kW, kH}, params);
    }
    auto all = load(stacked);
    ASSERT_TRUE(all);
    for (uint32_t f : {2u, 0u, 3u, 1u, 2u}) {  // switches back and forth
        auto single = load(alone[f]);
        ASSERT_TRUE(single);
        const ImageRGBA a = floor_after_effects(*all, f, 1.9);
        const ImageRGBA b = floor_after_effects(*single, 0, 1.9);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0)
            << "floor " << f << " in the stack equals the same floor alone";
    }
}

TEST_F(FireTest, OddCanvasesAndAnEmptyMask) {
    for (const auto& [w, h] : {std::pair{1u, 1u}, std::pair{37u, 23u}}) {
        SceneDesc scene = make_scene(w, h);
        const ImageRGBA tile = solid(w, h, {0.2f, 0.1f, 0.1f, 1});
        const uint32_t floor = fire_floor(scene, tile, block_mask(w, h, 0, 0, int(w), int(h)),
                                          {0, 0, double(w), double(h)}, test_params());
        auto compositor = load(scene);
        ASSERT_TRUE(compositor) << w << "x" << h;
        for (double time : {0.0, 1e5}) {
            const ImageRGBA out = floor_after_effects(*compositor, floor, time);
            ASSERT_EQ(out.width, w);
            for (float v : out.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
            for (size_t i = 3; i < out.pixels.size(); i += 4) ASSERT_LE(out.pixels[i], 1.0f);
        }
    }
    // An empty fire mask: the scene renders as without the effect, with the same passes.
    constexpr uint32_t kW = 40, kH = 30;
    const ImageRGBA tile = ground(kW, kH + 40);
    SceneDesc bare = make_scene(kW, kH + 40, {0, 0, 0, 1});
    fire_floor(bare, tile, block_mask(kW, kH + 40, 0, 0, 0, 0), {0, 0, kW, kH + 40}, nullptr);
    SceneDesc with = make_scene(kW, kH + 40, {0, 0, 0, 1});
    fire_floor(with, tile, block_mask(kW, kH + 40, 0, 0, 0, 0), {0, 0, kW, kH + 40}, test_params());
    auto a = load(bare), b = load(with);
    ASSERT_TRUE(a && b);
    FrameStats sa, sb;
    const ImageRGBA out_a = render(*a, 0, &sa), out_b = render(*b, 0, &sb);
    ASSERT_EQ(out_a.pixels.size(), out_b.pixels.size());
    EXPECT_EQ(
        std::memcmp(out_a.pixels.data(), out_b.pixels.data(), out_a.pixels.size() * sizeof(float)),
        0);
    EXPECT_EQ(sb.passes, sa.passes);
}

TEST_F(FireTest, TheSameTimeGivesTheSamePixelsAfterAReload) {
    constexpr uint32_t kW = 64, kH = 64;
    SceneDesc scene = make_scene(kW, kH);
    fire_floor(scene, ground(kW, kH), block_mask(kW, kH, 20, 40, 44, 46), {0, 0, kW, kH},
               nlohmann::json::object());
    auto first = load(scene), second = load(scene);
    ASSERT_TRUE(first && second);
    for (double time : {0.0, 0.37, 1.9, 1e5}) {
        const ImageRGBA a = floor_after_effects(*first, 0, time);
        const ImageRGBA b = floor_after_effects(*second, 0, time);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0)
            << "t = " << time;
    }
    EXPECT_GT(max_abs_difference(floor_after_effects(*first, 0, 1.9),
                                 floor_after_effects(*first, 0, 1.95)),
              0.01)
        << "the fire moves";
}

}  // namespace
}  // namespace acetate::test
