// acetate.bloom against a CPU model of the same algorithm in double precision, its energy
// balance, its behaviour near the half-float maximum and on tiny and odd canvases, and the
// targets a scene holds with and without it.

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <vector>

#include "render_fixture.hpp"

namespace acetate::test {
namespace {

struct BloomParams {
    double threshold = 1.0, knee = 0.5, intensity = 0.6, radius = 1.0;
    int levels = 5;         // the chain's last level
    int first = 1;          // its first: 1 = half, 2 = quarter, 3 = eighth size
    bool fine_tent = true;  // the finest upsample's tent (off: one bilinear tap)
    int count() const { return levels - first + 1; }
};

// ---- The CPU model: the same passes, taps, grid and clamping as plugins/bloom, in double. ----

using Rgb = std::array<double, 3>;

struct Level {
    int w = 0, h = 0;
    std::vector<Rgb> px;
    Level(int width, int height) : w(width), h(height), px(size_t(width) * height, Rgb{0, 0, 0}) {}
    Rgb& at(int x, int y) { return px[size_t(y) * w + x]; }
    // CLAMP_TO_EDGE fetch.
    const Rgb& fetch(int x, int y) const {
        return px[size_t(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1)];
    }
    // A LINEAR sample at (x, y) in texels (texel centres at i + 0.5), as the sampler does.
    Rgb bilinear(double x, double y) const {
        x -= 0.5;
        y -= 0.5;
        const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
        const int i = int(x0), j = int(y0);
        Rgb out{};
        for (int c = 0; c < 3; ++c)
            out[c] = (1 - fy) * ((1 - fx) * fetch(i, j)[c] + fx * fetch(i + 1, j)[c]) +
                     fy * ((1 - fx) * fetch(i, j + 1)[c] + fx * fetch(i + 1, j + 1)[c]);
        return out;
    }
};

int level_size(int canvas, int k) {
    return std::max(1, (canvas + (1 << k) - 1) >> k);
}
double max3(const Rgb& c) {
    return std::max({c[0], c[1], c[2]});
}
double luma(const Rgb& c) {
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

Rgb bright(Rgb c, const BloomParams& p) {
    const double cap = 65504.0 / 16.0;
    for (double& v : c) v = std::max(v, 0.0);
    const double t = p.threshold, k = t * p.knee, br = max3(c);
    double soft = std::clamp(br - t + k, 0.0, 2 * k);
    soft = k > 0 ? soft * soft / (4 * k) : 0.0;
    const double scale = br > 0 ? std::max(soft, br - t) / br : 0.0;
    const double m = br * scale;
    for (double& v : c) v *= scale * (cap / std::max(m, cap));
    return c;
}

// Returns the output rgba (premultiplied) for input rgba `in` (the composite the effect sees).
std::vector<std::array<double, 4>> cpu_bloom(const ImageRGBA& in, const BloomParams& p) {
    const int W = int(in.width), H = int(in.height), N = p.count();
    const double D = 1 << p.first;  // the first level's divisor
    Level prev(W, H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) prev.at(x, y)[c] = in.at(x, y)[c];
    std::vector<Level> down;
    for (int k = p.first; k <= p.levels; ++k) {
        Level out(level_size(W, k), level_size(H, k));
        const bool prefilter = k == p.first;
        const Level& src = prefilter ? prev : down.back();
        const double scale = prefilter ? D : 2;  // DIVISOR, or 2 for a down pass
        for (int j = 0; j < out.h; ++j)
            for (int i = 0; i < out.w; ++i) {
                const double cx = scale * (i + 0.5), cy = scale * (j + 0.5);  // x gl_FragCoord
                // Taps on texel corners: offsets -1, +1 per axis, or -3, -1, +1, +3 at 8.
                const int n = std::max(2, int(scale) / 2);
                std::vector<Rgb> taps;
                for (int ty = 0; ty < n; ++ty)
                    for (int tx = 0; tx < n; ++tx)
                        taps.push_back(src.bilinear(cx + 2 * tx + 1 - n, cy + 2 * ty + 1 - n));
                Rgb sum{};
                double weights = 0;
                for (Rgb& t : taps) {
                    double w = 1;
                    if (prefilter) {
                        t = bright(t, p);
                        w = 1 / (1 + luma(t));  // Karis average
                    }
                    for (int c = 0; c < 3; ++c) sum[c] += w * t[c];
                    weights += w;
                }
                for (int c = 0; c < 3; ++c) out.at(i, j)[c] = sum[c] / weights;
            }
        down.push_back(std::move(out));
    }
    Level bloom = down.back();  // upK = tent(up(K+1) or down(last)) + downK
    for (int k = p.levels - 1; k >= p.first; --k) {
        Level out = down[size_t(k - p.first)];
        const double r = p.radius;
        const int reach = k == p.first && !p.fine_tent ? 0 : 1;  // one tap, or the 3x3 tent
        for (int j = 0; j < out.h; ++j)
            for (int i = 0; i < out.w; ++i) {
                const double cx = 0.5 * (i + 0.5), cy = 0.5 * (j + 0.5);
                for (int dy = -reach; dy <= reach; ++dy)
                    for (int dx = -reach; dx <= reach; ++dx) {
                        const double w =
                            reach ? (2 - std::abs(dx)) * (2 - std::abs(dy)) / 16.0 : 1.0;
                        const Rgb s = bloom.bilinear(cx + dx * r, cy + dy * r);
                        for (int c = 0; c < 3; ++c) out.at(i, j)[c] += w * s[c];
                    }
            }
        bloom = std::move(out);
    }
    std::vector<std::array<double, 4>> result(size_t(W) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float* c = in.at(x, y);
            const Rgb b = bloom.bilinear((x + 0.5) / D, (y + 0.5) / D);
            std::array<double, 4>& o = result[size_t(y) * W + x];
            double added = 0;
            for (int k = 0; k < 3; ++k) {
                const double a = b[k] * p.intensity / N;
                o[k] = std::min(c[k] + a, 65504.0);
                added = std::max(added, a);
            }
            o[3] = c[3] + std::min(1.0, added) * std::max(0.0, 1.0 - c[3]);
        }
    return result;
}

// ---- Fixture ----

class BloomTest : public RenderTest {
  protected:
    static EffectRef bloom(nlohmann::json params = nlohmann::json::object(),
                           std::string preset = "") {
        EffectRef ref;
        ref.plugin = "acetate.bloom";
        ref.params = std::move(params);
        ref.preset = std::move(preset);
        ref.where = "global_effects[0]";
        return ref;
    }
    static nlohmann::json to_json(const BloomParams& p) {
        return {{"threshold", p.threshold}, {"knee", p.knee},     {"intensity", p.intensity},
                {"levels", p.levels},       {"radius", p.radius}, {"first_level", p.first},
                {"fine_tent", p.fine_tent}};
    }

    // One floor holding `tile` over the whole canvas, transparent background, bloom global.
    SceneDesc scene_with(const ImageRGBA& tile, const EffectRef& ref) {
        SceneDesc scene = make_scene(tile.width, tile.height, {0, 0, 0, 0});
        const uint32_t floor = add_floor(scene, "ground");
        add_tile(scene, floor, tile, {0, 0, double(tile.width), double(tile.height)});
        scene.global_effects = {ref};
        return scene;
    }

    // The composite after the global effects (the accumulation: no background mixed in).
    ImageRGBA run(const SceneDesc& scene, CompositorOptions options = {},
                  FrameStats* stats = nullptr) {
        auto compositor = load(scene, options);
        if (!compositor) return {};
        render(*compositor, scene.active_floor, stats);
        auto out = compositor->read_accumulation();
        if (!out) {
            ADD_FAILURE() << out.error().message;
            return {};
        }
        return std::move(out.value());
    }

    // What bloom sees: the same scene with intensity 0 (the composite is then the identity:
    // rgb + 0, alpha + 0), so the input goes through exactly the same floor path.
    ImageRGBA input_of(const ImageRGBA& tile, BloomParams p, CompositorOptions options = {}) {
        p.intensity = 0;
        return run(scene_with(tile, bloom(to_json(p))), options);
    }
};

void put(ImageRGBA& image, uint32_t x, uint32_t y, std::array<float, 4> rgba) {
    std::copy(rgba.begin(), rgba.end(), image.at(x, y));
}

// A small odd-sized scene: a dim premultiplied gradient with a transparent band, HDR spots
// (one on a corner), and a single 60000 firefly.
ImageRGBA spots_scene(uint32_t w, uint32_t h) {
    ImageRGBA tile(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float a = x < 8 ? 0.0f : std::min(1.0f, float(x - 8) / float(w / 2) + 0.1f);
            put(tile, x, y, {0.2f * a, 0.3f * a, 0.45f * a + 0.02f * float(y % 5) * a, a});
        }
    for (uint32_t y = 13; y < 16; ++y)
        for (uint32_t x = 19; x < 22; ++x) put(tile, x, y, {8, 6, 2, 1});
    for (uint32_t y = 30; y < 32 && y < h; ++y)
        for (uint32_t x = 44; x < 46 && x < w; ++x) put(tile, x, y, {50, 50, 50, 1});
    put(tile, w - 1, 0, {20, 5, 1, 1});  // a corner spot: edge clamping and partial texels
    put(tile, 2, h - 2, {3, 9, 30, 1});  // light inside the transparent band (alpha 1)
    put(tile, 30, h - 7, {60000, 60000, 60000, 1});  // firefly
    return tile;
}

// ---- Tests ----

// Tolerance, per channel: GPU = model within u * |out| + 2N * u * |added| + 1e-6, u = 2^-10.
// Why: every pass stores RGBA16F, one rounding of at most 1 ulp (2^-10 relative: Vulkan lets
// an attachment write round toward zero, and lavapipe does; the output's error is then just
// under 1 ulp, which is why the worst pixel sits at ~0.95 of this bound). The prefilter reads the
// exact input, so its non-linear steps (knee, Karis weights) see no error; every later step is a
// convex combination of non-negative values, which keeps a relative error bound and adds its
// own rounding. down_k so carries k*u, up_k max(up_{k+1}, down_k) + u, up1 (2N-1)*u; 2N leaves
// room for fp32 arithmetic and sample positions (~1e-5 relative, exact bilinear fractions at
// radius 1 and 1.25). The output adds one more rounding of the whole value (u * |out|), and
// half subnormals (spacing 6e-8) an absolute 1e-6. Alpha: b = min(1, max added) is
// 1-Lipschitz in the added light, so the same bound holds with b.
TEST_F(BloomTest, MatchesTheCpuModelForEveryPreset) {
    const ImageRGBA tile = spots_scene(61, 47);  // odd: partial texels at every level
    struct Case {
        std::string preset;
        BloomParams p;
    };
    std::vector<Case> cases;
    // The presets as bloom.cpp declares them: (first level, last level, fine tent).
    const std::tuple<const char*, int, int, bool> presets[] = {
        {"low", 3, 6, true}, {"medium", 2, 6, true}, {"high", 1, 6, false}, {"ultra", 1, 6, true}};
    for (const auto& [name, first, levels, fine_tent] : presets) {
        BloomParams p;
        p.first = first;
        p.levels = levels;
        p.fine_tent = fine_tent;
        cases.push_back({name, p});
    }
    BloomParams one;
    one.levels = 1;
    cases.push_back({"", one});
    BloomParams one_quarter;  // a single quarter-size level: the prefilter feeds the composite
    one_quarter.first = one_quarter.levels = 2;
    cases.push_back({"", one_quarter});
    BloomParams deep{0.5, 0.2, 2.0, 1.25, 8};
    cases.push_back({"", deep});
    BloomParams deep_quarter{0.5, 0.2, 2.0, 1.25, 8, 2, false};
    cases.push_back({"", deep_quarter});
    BloomParams one_eighth;  // the 16-tap prefilter straight into the composite
    one_eighth.first = one_eighth.levels = 3;
    cases.push_back({"", one_eighth});

    const ImageRGBA in = input_of(tile, BloomParams{});
    ASSERT_EQ(in.width, 61u);
    for (const Case& c : cases) {
        const std::string label = "levels " + std::to_string(c.p.first) + ".." +
                                  std::to_string(c.p.levels) +
                                  (c.p.fine_tent ? "" : ", one-tap finest upsample");
        SCOPED_TRACE(c.preset.empty() ? label : c.preset + ", " + label);
        const EffectRef ref = c.preset.empty() ? bloom(to_json(c.p)) : bloom({}, c.preset);
        const ImageRGBA out = run(scene_with(tile, ref));
        ASSERT_EQ(out.width, 61u);
        const auto expected = cpu_bloom(in, c.p);
        const double u = 1.0 / 1024;
        double worst = 0;  // largest error as a fraction of its tolerance
        int failures = 0;
        for (uint32_t y = 0; y < in.height; ++y)
            for (uint32_t x = 0; x < in.width; ++x) {
                const auto& e = expected[size_t(y) * in.width + x];
                const float* in_px = in.at(x, y);
                const float* got = out.at(x, y);
                double added_max = 0;
                for (int k = 0; k < 3; ++k) added_max = std::max(added_max, e[k] - in_px[k]);
                for (int k = 0; k < 4; ++k) {
                    const double added = k < 3 ? e[k] - in_px[k] : std::min(1.0, added_max);
                    const double tol = u * std::fabs(e[k]) + 2 * c.p.count() * u * added + 1e-6;
                    const double err = std::fabs(got[k] - e[k]);
                    worst = std::max(worst, err / tol);
                    if (err > tol && ++failures <= 5)
                        ADD_FAILURE()
                            << "pixel " << x << "," << y << " channel " << k << ": got " << got[k]
                            << ", model " << e[k] << " (tolerance " << tol << ")";
                }
            }
        std::printf("[ bloom    ] %-8s %s: worst error %.3f of tolerance\n", c.preset.c_str(),
                    label.c_str(), worst);
        if (failures) {
            ImageRGBA model(in.width, in.height);
            for (size_t i = 0; i < expected.size(); ++i)
                for (int k = 0; k < 4; ++k) model.pixels[i * 4 + k] = float(expected[i][k]);
            ADD_FAILURE() << failures << " channels off; images in "
                          << save_failure_images("bloom_" + std::to_string(c.p.first) + "_" +
                                                     std::to_string(c.p.levels),
                                                 out, model);
        }
        // The bloom is really there: the pixel beside the 8/6/2 spot gained light (0.02 with
        // the low preset, whose eighth-size first level spreads the spot widest; over 0.05 in
        // every other case).
        EXPECT_GT(out.at(23, 14)[0], in.at(23, 14)[0] + 0.01f);
    }
}

// Energy, threshold 0 and knee 0 (the bright-pass is the identity), RGBA32F targets so storage
// rounding is ~1e-7 and the balance itself is what is measured.
//
// Why it balances: in the 4x4 box (down) every input texel is read by two outputs per axis at
// 1/4 each: 1/2 per axis x 2 (area ratio) = 1. On even sizes the edges balance too: the edge
// texel is read by one output only, but twice (its own tap and the clamped one). The 9-tap tent
// sums to 1 and bilinear taps at half-texel spacing give every coarse texel a total weight of 4
// fine texels = its area; the composite's single bilinear tap likewise. So the chain preserves
// energy, and the composite divides up1 (the sum of N levels) by N: added energy = intensity x
// bright-pass energy. The one exception is the tent's clamp at an edge (radius 1): summing its taps
// per coarse texel, the edge texel gives 33/32 of its energy and the one next to it 31/32 (per
// axis; all others exactly 1). A level-k contribution passes k-1 tents, so whatever the picture,
//   added / (intensity x energy) lies in [ mean_k (31/32)^(2(k-1)), mean_k (33/32)^(2(k-1)) ]
// ([0.9397, 1.0648] for 3 levels, [0.8843, 1.1353] for 5), and is exactly 1 for light whose
// filter reach never touches an edge. Clamping never discards a tap, so nothing is lost beyond
// the 31/32 case.
// Karis weights depend on tap luminance, which would bias the mean, so the picture has ONE
// luminance everywhere: a grey ground (constant, so it blooms to itself exactly, clamping or
// not) and a blob of pure blue with the same luminance; the balance is measured on the blob's
// difference from the ground (+12.9 x grey in blue, -grey in red and green).
// Precision bound per channel: fp32 storage and ~12 operations per pass over 2N passes, plus
// the final sum: 2^-24 x (in + 25 N x added) summed over the canvas, relative to the blob's
// expected added energy.
class BloomEnergyTest : public BloomTest {
  protected:
    struct Balance {
        double ratio[3];      // added blob energy / (intensity x blob energy), per channel
        double precision[3];  // the bound above
    };
    Balance balance(uint32_t x0, uint32_t y0, uint32_t w, uint32_t h, int levels, int first = 1) {
        const uint32_t W = 256, H = 256;
        const float grey = 0.05f;
        const float blue = float(grey / 0.0722);  // luminance 0.0722 x blue == grey
        ImageRGBA tile = solid(W, H, {grey, grey, grey, 1});
        for (uint32_t y = y0; y < y0 + h; ++y)
            for (uint32_t x = x0; x < x0 + w; ++x) put(tile, x, y, {0, 0, blue, 1});
        BloomParams p{0.0, 0.0, 0.6, 1.0, levels, first};
        CompositorOptions options;
        options.format = VK_FORMAT_R32G32B32A32_SFLOAT;
        const ImageRGBA in = input_of(tile, p, options);
        const ImageRGBA out = run(scene_with(tile, bloom(to_json(p))), options);
        Balance result{};
        if (out.width != W || in.width != W) {
            ADD_FAILURE() << "no image";
            return result;
        }
        for (int c = 0; c < 3; ++c) {
            double energy = 0, added = 0, bound = 0;
            for (uint32_t y = 0; y < H; ++y)
                for (uint32_t x = 0; x < W; ++x) {
                    const double a = double(out.at(x, y)[c]) - in.at(x, y)[c];
                    energy += in.at(x, y)[c];
                    added += a;
                    bound += std::ldexp(in.at(x, y)[c] + 25 * p.count() * std::fabs(a), -24);
                }
            const double ground = double(grey) * W * H;
            const double blob_energy = energy - ground;  // negative for red and green
            result.ratio[c] = (added - p.intensity * ground) / (p.intensity * blob_energy);
            result.precision[c] = bound / std::fabs(p.intensity * blob_energy);
        }
        return result;
    }
};

TEST_F(BloomEnergyTest, InteriorLightIsNeitherLostNorInvented) {
    // Blob [80,176)^2 of 256^2, 3 levels: the filters' reach (down: to 24 px past the blob at
    // level 3; tents: 1.5 coarse texels, 24 + 12 px; composite 2 px) stays inside [18, 238), so
    // no tap of the blob's light is ever clamped and the ratio is exactly 1.
    const Balance b = balance(80, 80, 96, 96, 3);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(b.ratio[c], 1.0, b.precision[c]) << "channel " << c;
        std::printf("[ bloom    ] interior blob: channel %d energy ratio %.7f (bound 1 +- %.1e)\n",
                    c, b.ratio[c], b.precision[c]);
    }
}

TEST_F(BloomEnergyTest, AQuarterSizeChainBalancesToo) {
    // Levels 2..4 (the low preset's chain), blob [96,160)^2: the prefilter's 4x4 box at
    // DIVISOR 4 reads each texel once, the down passes spread 4 and 8 px, the tents 1.5 coarse
    // texels (24 + 12 px) and the composite's quarter-size tap 4 px: nothing reaches an edge.
    const Balance b = balance(96, 96, 64, 64, 4, 2);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(b.ratio[c], 1.0, b.precision[c]) << "channel " << c;
        std::printf(
            "[ bloom    ] quarter-size chain: channel %d energy ratio %.7f (bound 1 +- "
            "%.1e)\n",
            c, b.ratio[c], b.precision[c]);
    }
}

TEST_F(BloomEnergyTest, EdgeLightStaysWithinTheClampBound) {
    struct Blob {
        uint32_t x0, y0, w, h;
    };
    // A one-pixel strip along the left edge and an 8x8 blob in the top-left corner: the
    // double-precision model of this chain gives 1.022 and 1.014 (3 levels), 1.027 and 1.031 (5).
    for (int levels : {3, 5}) {
        double lo = 0, hi = 0;
        for (int k = 1; k <= levels; ++k) {
            lo += std::pow(31.0 / 32, 2 * (k - 1)) / levels;
            hi += std::pow(33.0 / 32, 2 * (k - 1)) / levels;
        }
        for (const Blob& blob : {Blob{0, 0, 1, 256}, Blob{0, 0, 8, 8}}) {
            const Balance b = balance(blob.x0, blob.y0, blob.w, blob.h, levels);
            for (int c = 0; c < 3; ++c) {
                SCOPED_TRACE(std::to_string(levels) + " levels, blob " + std::to_string(blob.w) +
                             "x" + std::to_string(blob.h) + ", channel " + std::to_string(c));
                EXPECT_GE(b.ratio[c], lo - b.precision[c]);
                EXPECT_LE(b.ratio[c], hi + b.precision[c]);
                EXPECT_GT(b.ratio[c], 1.0);  // the clamp adds, as the model says, and is seen
                std::printf(
                    "[ bloom    ] edge blob %ux%u, %d levels: channel %d ratio %.5f in "
                    "[%.4f, %.4f] (precision %.1e)\n",
                    blob.w, blob.h, levels, c, b.ratio[c], lo, hi, b.precision[c]);
            }
        }
    }
}

// Inputs at the half-float maximum and 60000 fireflies, at the strongest settings: no NaN or
// Inf anywhere (the bright-pass is capped at 65504/16 so 8 summed levels stay finite, and the
// composite clamps at 65504), alpha never drops, transparent pixels stay zero.
TEST_F(BloomTest, HalfFloatMaximumAndFirefliesStayFinite) {
    ImageRGBA tile(67, 45);
    for (uint32_t y = 0; y < 45; ++y)
        for (uint32_t x = 0; x < 67; ++x) {
            if (x < 20) continue;  // transparent
            if (x < 40 && y < 30)
                put(tile, x, y, {65504, 65504, 65504, 1});
            else if ((x * 7 + y * 13) % 17 == 0)
                put(tile, x, y, {60000, 60000, 60000, 1});
            else
                put(tile, x, y, {0.5f, 0.25f, 65504, 1});
        }
    put(tile, 10, 10, {60000, 30000, 60000, 1});  // a firefly in the transparent part
    const ImageRGBA in = input_of(tile, BloomParams{});
    const ImageRGBA out =
        run(scene_with(tile, bloom({{"threshold", 0}, {"intensity", 4}, {"radius", 2}}, "ultra")));
    ASSERT_EQ(out.width, 67u);
    for (uint32_t y = 0; y < 45; ++y)
        for (uint32_t x = 0; x < 67; ++x) {
            const float* p = out.at(x, y);
            for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c])) << x << "," << y;
            ASSERT_GE(p[3], in.at(x, y)[3]) << x << "," << y;
            ASSERT_LE(p[3], 1.0f);
            if (p[3] == 0) {
                ASSERT_EQ(p[0] + p[1] + p[2], 0.0f) << x << "," << y;
            }
        }
    EXPECT_GT(out.at(5, 40)[2], 1.0f);  // the light did spread into the transparent part
}

// A lone 60000 white pixel on black: its tap gets Karis weight 1/(1 + 4094) against three dark
// taps of weight 1, so down1 <= 4094/4095 / (3 + 1/4095) < 1/3, every level and the average of
// N levels stay below 1/3, and no pixel gains more than intensity / 3. Without the Karis
// average the same pixel would add ~intensity x 4094 / 4 / N.
TEST_F(BloomTest, AFireflyAddsAtMostAThirdOfIntensity) {
    ImageRGBA tile(48, 40);
    put(tile, 21, 17, {60000, 60000, 60000, 1});
    const ImageRGBA out = run(scene_with(tile, bloom()));
    ASSERT_EQ(out.width, 48u);
    double peak = 0;
    for (uint32_t y = 0; y < 40; ++y)
        for (uint32_t x = 0; x < 48; ++x)
            if (x != 21 || y != 17) peak = std::max(peak, double(out.at(x, y)[0]));
    EXPECT_LE(peak, 0.6 / 3 * (1 + 11.0 / 1024));  // 2N + 1 roundings of 2^-10
    EXPECT_GT(peak, 0.01);                         // it still blooms
}

// Tiny and odd canvases: no validation message (TearDown), finite output, alpha never lower
// than the input's, (0, 0, 0, 0) where alpha is 0; and the pixels shaded are the ones bloom.cpp
// documents: the composite over the canvas, down passes over levels 1..L, up passes 1..L-1.
TEST_F(BloomTest, TinyAndOddCanvasesKeepTheContract) {
    for (const auto& [w, h] : {std::pair{1u, 1u}, std::pair{2u, 2u}, std::pair{1921u, 1079u}}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
        ImageRGBA tile(w, h);
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                const float a =
                    (x + 2 * y) % 5 == 0 ? 0.0f : float((x * 31 + y * 17) % 100) / 99.0f;
                const float v = (x * 13 + y * 7) % 97 == 0 ? 300.0f : 0.7f;
                put(tile, x, y, {v * a, 0.5f * v * a, 0.25f * a, a});
            }
        FrameStats stats;
        const ImageRGBA out = run(scene_with(tile, bloom()), {}, &stats);
        ASSERT_EQ(out.width, w);
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                const float* p = out.at(x, y);
                for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c])) << x << "," << y;
                // The input alpha: the tile's, in half (one tile over a transparent ground).
                ASSERT_GE(p[3], float(Imath::half(tile.at(x, y)[3]))) << x << "," << y;
                if (p[3] == 0.0f) {
                    for (int c = 0; c < 3; ++c) ASSERT_EQ(p[c], 0.0f) << x << "," << y;
                }
            }
        uint64_t pixels = uint64_t(w) * h;
        for (int k = 1; k <= 5; ++k)
            pixels += uint64_t(level_size(int(w), k)) * level_size(int(h), k) * (k < 5 ? 2 : 1);
        std::printf("[ bloom    ] %ux%u: frame %.1f ms, bloom %llu pixels shaded\n", w, h,
                    stats.milliseconds, (unsigned long long)pixels);
        ASSERT_TRUE(stats.global.has_value());
        EXPECT_EQ(stats.global->pixels_shaded, pixels);
        EXPECT_EQ(stats.global->passes, 10u);
    }
}

TEST_F(BloomTest, ASceneWithoutBloomHoldsNoBloomTargets) {
    const ImageRGBA tile = solid(40, 30, {2, 2, 2, 1});
    SceneDesc scene = scene_with(tile, bloom({}, "low"));
    auto with = load(scene);
    ASSERT_TRUE(with);
    std::vector<std::string> names;
    for (const TargetInfo& t : with->targets_held())
        if (t.name.find("acetate.bloom") != std::string::npos) names.push_back(t.name);
    // low = levels 3..6: down3..down6 and up3..up5, ceil(canvas / 2^k) in size; no half- or
    // quarter-size target at all.
    EXPECT_EQ(names.size(), 7u);
    for (const TargetInfo& t : with->targets_held()) {
        for (const char* finer : {"down1", "up1", "down2", "up2"})
            EXPECT_NE(t.name, std::string("acetate.bloom.") + finer);
        if (t.name == "acetate.bloom.down3") {
            EXPECT_EQ(t.width, 5u);
            EXPECT_EQ(t.height, 4u);
        }
    }
    scene.global_effects.clear();
    auto without = load(scene);
    ASSERT_TRUE(without);
    for (const TargetInfo& t : without->targets_held())
        EXPECT_EQ(t.name.find("acetate.bloom"), std::string::npos) << t.name;
}

}  // namespace
}  // namespace acetate::test
