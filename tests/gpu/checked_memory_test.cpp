// The two options the validation harness uses to make undefined behaviour visible
// (CompositorOptions): `poison`, a sentinel in the memory an effect may read before writing it,
// and `checked_builtins`, min, max, clamp and smoothstep that give NaN where GLSL leaves the
// result to the driver. Broken test plugins show that each catches what it should; the shipped
// plugins show that a correct effect renders bit for bit the same with them.

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>

#include "plugins/plugin_loader.hpp"
#include "render/effect_pipelines.hpp"
#include "render_fixture.hpp"
#include "vulkan/shader_compiler.hpp"

namespace acetate::test {
namespace {

using Rgba = std::array<float, 4>;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr Rgba kZero{0, 0, 0, 0};
constexpr Rgba kNaNs{kNaN, kNaN, kNaN, kNaN};

// Equal, with NaN equal to any NaN (the payload is the driver's business).
bool same(float actual, float expected) {
    return std::isnan(expected) ? std::isnan(actual) : actual == expected;
}

// "" when every pixel is what `expected` says, else the first pixel that is not.
std::string first_mismatch(const ImageRGBA& image,
                           const std::function<Rgba(uint32_t, uint32_t)>& expected) {
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const Rgba want = expected(x, y);
            const float* p = image.at(x, y);
            for (int c = 0; c < 4; ++c)
                if (!same(p[c], want[c]))
                    return fmt::format("({},{}) is ({}, {}, {}, {}), expected ({}, {}, {}, {})", x,
                                       y, p[0], p[1], p[2], p[3], want[0], want[1], want[2],
                                       want[3]);
        }
    return "";
}

std::string describe(const std::optional<Rgba>& poison) {
    if (!poison) return "unset";
    const Rgba& p = *poison;
    return fmt::format("({}, {}, {}, {})", p[0], p[1], p[2], p[3]);
}

bool bit_identical(const ImageRGBA& a, const ImageRGBA& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

class CheckedMemory : public RenderTest {
  protected:
    static EffectRef effect(const std::string& plugin, uint32_t floor, uint32_t index = 0) {
        EffectRef ref;
        ref.plugin = plugin;
        ref.where = fmt::format("floors[{}].effects[{}]", floor, index);
        return ref;
    }
    // `floors` floors of one opaque tile at `rect`, each carrying `plugin`.
    SceneDesc scene_with(const std::string& plugin, uint32_t width, uint32_t height,
                         uint32_t floors, SceneRect rect) {
        SceneDesc scene = make_scene(width, height);
        for (uint32_t f = 0; f < floors; ++f) {
            const uint32_t floor = add_floor(scene, fmt::format("floor{}", f));
            add_tile(scene, floor,
                     solid(uint32_t(rect.width), uint32_t(rect.height), {0.5f, 0.25f, 0.125f, 1}),
                     rect);
            scene.floors[floor].effects = {effect(plugin, floor)};
        }
        return scene;
    }
    // Loaded as the harness loads: the active floor's whole target is drawn and kept.
    std::unique_ptr<Compositor> load_floor_view(const SceneDesc& scene, CompositorOptions options) {
        options.view = OutputView::FloorRgb;
        return load(scene, options);
    }
    // Renders `floor` and returns its whole target after its effects.
    ImageRGBA floor_frame(Compositor& compositor, uint32_t floor) {
        render(compositor, floor);
        auto target = compositor.read_active_floor();
        if (!target) {
            ADD_FAILURE() << "read_active_floor: " << target.error().message;
            return {};
        }
        return std::move(target.value());
    }
};

TEST_F(CheckedMemory, ResultPixelsAnEffectDoesNotWriteHoldThePoisonInsideItsScissorOnly) {
    // The tile covers x 4..11, y 2..5: the floor's scissor. test.discards_half writes the even
    // columns of "result" there and discards the odd ones.
    const SceneDesc scene = scene_with("test.discards_half", 16, 8, 1, {4, 2, 8, 4});
    const Rgba tile{0.5f, 0.25f, 0.125f, 1};
    const std::optional<Rgba> poisons[] = {std::nullopt, kNaNs, Rgba{0.25f, -2.0f, 1024.0f, 3.0f}};
    for (const std::optional<Rgba>& poison : poisons) {
        CompositorOptions options;
        options.poison = poison;
        auto compositor = load_floor_view(scene, options);
        ASSERT_TRUE(compositor);
        for (int frame = 0; frame < 2; ++frame) {
            const ImageRGBA target = floor_frame(*compositor, 0);
            // Without poison, the discarded pixels keep today's zeros; outside the scissor the
            // target is zero either way (the harness reads the whole target).
            EXPECT_EQ(first_mismatch(target,
                                     [&](uint32_t x, uint32_t y) {
                                         const bool inside = x >= 4 && x < 12 && y >= 2 && y < 6;
                                         if (!inside) return kZero;
                                         if (x % 2 == 0) return tile;
                                         return poison.value_or(kZero);
                                     }),
                      "")
                << "poison " << describe(poison) << ", frame " << frame;
        }
    }
}

TEST_F(CheckedMemory, TargetsArePoisonedOnceAtLoadNotBetweenFloorsOrFrames) {
    // test.partial_target on two floors shares one target: floor 0 writes its left two thirds
    // (0.25 red), floor 1 the middle third (0.5 red), nobody the right third; each shows it.
    const SceneDesc scene = scene_with("test.partial_target", 12, 4, 2, {0, 0, 12, 4});
    const Rgba floor0{0.25f, 0, 0, 1}, floor1{0.5f, 0, 0, 1};
    for (const Rgba& poison : {Rgba{0.125f, 0.5f, 2.0f, 4.0f}, kNaNs}) {
        CompositorOptions options;
        options.poison = poison;
        options.plan.cull_hidden_floors = false;  // floor 0 runs under floor 1's opaque tile
        auto compositor = load_floor_view(scene, options);
        ASSERT_TRUE(compositor);
        // Floor 1's frame runs floor 0's instance first: floor 1 must see what it wrote, not
        // the poison again. Then floor 0 alone, then floor 1 again in a later frame.
        const std::pair<uint32_t, std::function<Rgba(uint32_t)>> frames[] = {
            {1, [&](uint32_t x) { return x < 4   ? floor0
                                         : x < 8 ? floor1
                                                 : poison; }},
            {0, [&](uint32_t x) { return x < 8 ? floor0 : poison; }},
            {1, [&](uint32_t x) { return x < 4   ? floor0
                                         : x < 8 ? floor1
                                                 : poison; }},
        };
        int frame = 0;
        for (const auto& [floor, by_column] : frames) {
            const ImageRGBA target = floor_frame(*compositor, floor);
            EXPECT_EQ(first_mismatch(target, [&](uint32_t x, uint32_t) { return by_column(x); }),
                      "")
                << "poison " << describe(poison) << ", frame " << frame << " (floor " << floor
                << ")";
            ++frame;
        }
    }
}

TEST_F(CheckedMemory, ClampAndSmoothstepGiveNaNOnlyWhenChecked) {
    // test.nan_builtins: r = clamp(NaN made at run time, 0, 1), g = smoothstep(1, 0, 0.5),
    // b = correct uses of every other form, a = 1.
    const SceneDesc scene = scene_with("test.nan_builtins", 8, 8, 1, {0, 0, 8, 8});
    CompositorOptions options;
    auto unchecked = load_floor_view(scene, options);
    ASSERT_TRUE(unchecked);
    options.checked_builtins = true;
    auto checked = load_floor_view(scene, options);
    ASSERT_TRUE(checked);
    // The checked pass is a shader of its own: the pool keys SPIR-V by the whole source.
    EXPECT_GT(checked->load_stats().shaders_compiled, 0u);
    EXPECT_GT(checked->load_stats().pipelines_created, 0u);
    for (const Compositor* c : {unchecked.get(), checked.get()}) {
        EXPECT_EQ(c->effect_pass_counts().glsl, 1u);
        EXPECT_EQ(c->effect_pass_counts().spirv, 0u);
    }

    const ImageRGBA plain = floor_frame(*unchecked, 0);
    const ImageRGBA nan = floor_frame(*checked, 0);
    ASSERT_EQ(plain.pixels.size(), nan.pixels.size());
    const bool llvmpipe = context().device_name().find("llvmpipe") != std::string::npos;
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            const float* p = plain.at(x, y);
            const float* n = nan.at(x, y);
            EXPECT_TRUE(std::isnan(n[0])) << "checked clamp(NaN, 0, 1) at " << x << "," << y;
            EXPECT_TRUE(std::isnan(n[1])) << "checked smoothstep(1, 0, x) at " << x << "," << y;
            // llvmpipe's min and max return the other operand, so the NaN disappears; another
            // driver may keep it, which is why the harness checks with checked_builtins.
            if (llvmpipe) {
                EXPECT_TRUE(std::isfinite(p[0])) << "llvmpipe clamp(NaN, 0, 1) = " << p[0];
                EXPECT_TRUE(std::isfinite(p[1])) << "llvmpipe smoothstep(1, 0, x) = " << p[1];
            }
            EXPECT_TRUE(std::isfinite(p[2]) && p[2] > 0) << p[2];
            EXPECT_EQ(std::memcmp(&p[2], &n[2], 2 * sizeof(float)), 0)
                << "the correct uses differ at " << x << "," << y << ": " << p[2] << " vs " << n[2];
        }

    // Both variants stay in the pool: loading the unchecked scene again compiles nothing and
    // renders what it rendered before.
    options.checked_builtins = false;
    auto again = load_floor_view(scene, options);
    ASSERT_TRUE(again);
    EXPECT_EQ(again->load_stats().shaders_compiled, 0u);
    EXPECT_EQ(again->load_stats().pipelines_created, 0u);
    EXPECT_TRUE(bit_identical(floor_frame(*again, 0), plain));
}

TEST_F(CheckedMemory, CorrectEffectsRenderBitIdenticalWithBothOptions) {
    // acetate.lighting (int min, clamp) on the floor and acetate.bloom (min, max, clamp) on the
    // composite write every pixel before reading it and never feed NaN to a built-in.
    SceneDesc scene = make_scene(64, 48, {0.05f, 0.05f, 0.1f, 1});
    const uint32_t floor = add_floor(scene, "ground");
    ImageRGBA tile(48, 40);
    for (uint32_t y = 0; y < tile.height; ++y)
        for (uint32_t x = 0; x < tile.width; ++x) {
            const float a = x % 12 == 0 ? 0.0f : 0.3f + 0.7f * float(y) / float(tile.height);
            const float v = (x / 6 + y / 5) % 3 == 0 ? 4.0f : 0.4f;  // some HDR for the bloom
            float* p = tile.at(x, y);
            p[0] = v * a;
            p[1] = 0.5f * v * a;
            p[2] = 0.25f * a;
            p[3] = a;
        }
    add_tile(scene, floor, tile, {8, 4, 48, 40});
    scene.floors[floor].lights = {{{20, 20}, 30, {1, 0.8f, 0.6f}, 2.0f}};
    scene.floors[floor].effects = {effect("acetate.lighting", floor)};
    EffectRef bloom;
    bloom.plugin = "acetate.bloom";
    bloom.where = "global_effects[0]";
    scene.global_effects = {bloom};

    std::optional<ImageRGBA> reference;
    EffectPassCounts reference_counts;
    for (const bool checked : {false, true})
        for (const bool poisoned : {false, true}) {
            CompositorOptions options;
            options.checked_builtins = checked;
            if (poisoned) options.poison = kNaNs;
            auto compositor = load(scene, options);
            ASSERT_TRUE(compositor);
            // The checked passes are shaders of their own (so the comparison means something).
            if (checked && !poisoned) {
                EXPECT_GT(compositor->load_stats().shaders_compiled, 0u);
            }
            const EffectPassCounts counts = compositor->effect_pass_counts();
            EXPECT_GT(counts.glsl, 1u);
            EXPECT_EQ(counts.spirv, 0u);
            render(*compositor, floor);  // a first frame: the second must not see it either
            const ImageRGBA out = render(*compositor, floor);
            const std::string what = fmt::format("checked {}, poisoned {}", checked, poisoned);
            if (!reference) {
                reference = out;
                reference_counts = counts;
                for (float v : out.pixels) ASSERT_TRUE(std::isfinite(v)) << what;
                continue;
            }
            EXPECT_EQ(counts.glsl, reference_counts.glsl) << what;
            EXPECT_TRUE(bit_identical(out, *reference))
                << what << ": differs by up to " << max_abs_difference(out, *reference);
        }
}

TEST_F(CheckedMemory, PassesGivenAsSpirvAreCountedApartAndRunUnchecked) {
    // test.spirv_pass ships its pass compiled (ACETATE_TEST_SPIRV_FILE stands in for the
    // plugin's own SPIR-V); test.nan_builtins after it is GLSL and gets checked.
    auto plugin = renderer().plugins().load("test.spirv_pass");
    ASSERT_TRUE(plugin.ok()) << plugin.error().message;
    auto spirv = compile_glsl(
        "gain", ShaderStage::Fragment,
        effect_glsl_preamble(plugin.value()->descriptor, {"previous"}, ACETATE_PASS_FULLSCREEN,
                             false, FrameBlockDeclaration::Uniform) +
            "void main() { vec4 c = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);\n"
            "              out_color = vec4(c.rgb * param_gain, c.a); }\n");
    ASSERT_TRUE(spirv.ok()) << spirv.error().message;
    const auto file = dir() / "gain.spv";
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(spirv->data()), std::streamsize(spirv->size() * 4));

    SceneDesc scene = scene_with("test.nan_builtins", 8, 8, 1, {0, 0, 8, 8});
    scene.floors[0].effects = {effect("test.spirv_pass", 0, 0), effect("test.nan_builtins", 0, 1)};
    CompositorOptions options;
    options.checked_builtins = true;
    setenv("ACETATE_TEST_SPIRV_FILE", file.c_str(), 1);
    auto compositor = load_floor_view(scene, options);
    unsetenv("ACETATE_TEST_SPIRV_FILE");
    ASSERT_TRUE(compositor);
    EXPECT_EQ(compositor->effect_pass_counts().glsl, 1u);
    EXPECT_EQ(compositor->effect_pass_counts().spirv, 1u);
    const ImageRGBA target = floor_frame(*compositor, 0);
    EXPECT_TRUE(std::isnan(target.at(3, 3)[0]));
    EXPECT_EQ(target.at(3, 3)[3], 1.0f);  // the SPIR-V pass ran: alpha kept, colour halved
}

TEST_F(CheckedMemory, CheckedPreambleKeepsThePluginsLineNumbers) {
    // The checked helpers come before "#line 1": an error is still reported at the plugin's
    // own line, and an integer-only use of min compiles.
    EffectDescriptor descriptor;
    descriptor.id = "test.lines";
    const std::string body = "void main() {\n  int i = min(1, 2);\n  undeclared_thing = 1.0;\n}\n";
    auto compiled =
        compile_glsl("lines", ShaderStage::Fragment,
                     effect_glsl_preamble(descriptor, {}, ACETATE_PASS_FULLSCREEN, true) + body);
    ASSERT_FALSE(compiled.ok());
    EXPECT_NE(compiled.error().message.find(":3:"), std::string::npos) << compiled.error().message;
    EXPECT_EQ(compiled.error().message.find("acetate_checked_min"), std::string::npos)
        << compiled.error().message;
}

}  // namespace
}  // namespace acetate::test
