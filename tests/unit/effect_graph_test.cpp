// The effect graph without a GPU: an in-process fake plugin (no shared library, no Vulkan
// device) declares targets, passes, textures and floor data through the AcetateHostApi, and every
// refusal the host makes is checked as the exact one-line message naming the instance, pass and
// resource -- the same checks tests/gpu/plugin_abi_test.cpp proves through a device.

#include "fake_plugin.hpp"

namespace acetate::fake {
namespace {

// ---- What the host records, and what it checks after build(). ----

TEST(EffectGraph, ADeclaredGraphIsRecordedAsDeclared) {
    Fake fake;
    auto graph = fake.build([](Host& h) {
        h.target("bright", 2).target("wide", 4096).texture("ramp", 2, 1, 0.25f);
        h.floor_data({1, 2, 3, 4, 5}).floor_data({1, 2, 3, 4});  // the second replaces
        h.pass({.name = "pick", .inputs = {"previous", "mask.water"}, .output = "bright"})
            .pass({.name = "spread", .inputs = {"bright"}, .output = "wide"})
            .pass({.name = "add", .inputs = {"texture.ramp"}, .output = "wide", .blend = kAdd})
            .pass(
                {.name = "final", .inputs = {"previous", "wide"}, .glsl = nullptr, .spirv = kSpirv})
            .pass({.name = "sparks",
                   .inputs = {},
                   .blend = kOver,
                   .kind = kQuads,
                   .instance_count = 1});
        h.api->log(h.graph, "built");
    });
    ASSERT_TRUE(graph) << graph.error().message;
    const EffectGraph& g = graph.value();
    ASSERT_EQ(g.targets.size(), 2u);
    EXPECT_EQ(g.targets[0].name, "bright");
    EXPECT_EQ(g.targets[0].divisor, 2u);
    EXPECT_EQ(g.targets[0].format, ACETATE_FORMAT_FLOOR);
    EXPECT_EQ(g.targets[1].divisor, 4096u);
    ASSERT_EQ(g.textures.size(), 1u);
    EXPECT_EQ(g.textures[0].texels, std::vector<float>(8, 0.25f));
    EXPECT_EQ(g.floor_data, (std::vector<float>{1, 2, 3, 4}));
    EXPECT_EQ(g.log, std::vector<std::string>{at("built")});
    ASSERT_EQ(g.passes.size(), 5u);
    EXPECT_EQ(g.passes[0].inputs, (std::vector<std::string>{"previous", "mask.water"}));
    EXPECT_EQ(g.passes[0].input_names, (std::vector<std::string>{"previous", "mask_water"}));
    EXPECT_EQ(g.passes[0].glsl, kGlsl);
    EXPECT_EQ(g.passes[2].blend, kAdd);
    EXPECT_EQ(g.passes[3].spirv, kSpirv);
    EXPECT_TRUE(g.passes[3].glsl.empty());
    EXPECT_EQ(g.passes[4].kind, kQuads);
    EXPECT_EQ(g.passes[4].instance_count, 1u);
    EXPECT_TRUE(g.phases.empty());
    EXPECT_FALSE(g.reach.has_value());
}

// A build() that declares nothing is a pass-through the host drops; declaring anything without
// a pass that writes "result" is still refused.
TEST(EffectGraph, DeclaringNothingIsAPassThroughAndDeclaringHalfIsRefused) {
    Fake fake;
    auto nothing = fake.build([](Host&) {});
    ASSERT_TRUE(nothing) << nothing.error().message;
    EXPECT_TRUE(nothing->passes.empty());
    auto half = fake.build([](Host& h) { h.texture("ramp", 1, 1); });
    ASSERT_FALSE(half);
    EXPECT_EQ(half.error().message, at("no pass writes \"result\""));
}

// 1.1: a texture in a one- or two-channel format holds that many floats per texel; only
// add_texture_format reads the format (add_texture_info never did).
TEST(EffectGraph, TextureFormatsSetTheFloatsPerTexel) {
    Fake fake;
    const std::vector<float> data{1, 2, 3, 4, 5, 6, 7, 8};
    auto graph = fake.build([&](Host& h) {
        for (const auto& [name, format] :
             {std::pair{"r", ACETATE_FORMAT_R16F}, std::pair{"rg", ACETATE_FORMAT_RG32F}}) {
            const AcetateTextureInfo t{sizeof(AcetateTextureInfo), name, 2, 1, data.data(), format};
            h.note(h.api->add_texture_format(h.graph, &t));
        }
        const AcetateTextureInfo info{sizeof(AcetateTextureInfo), "info", 2, 1, data.data(),
                                      ACETATE_FORMAT_R16F};
        h.note(h.api->add_texture_info(h.graph, &info));
        h.pass({});
    });
    ASSERT_TRUE(graph) << graph.error().message;
    const auto& t = graph->textures;
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0].format, ACETATE_FORMAT_R16F);
    EXPECT_EQ(t[0].texels, (std::vector<float>{1, 2}));
    EXPECT_EQ(t[1].channels, 2u);
    EXPECT_EQ(t[1].texels, (std::vector<float>{1, 2, 3, 4}));
    EXPECT_EQ(t[2].format, ACETATE_FORMAT_FLOOR) << "add_texture_info does not read format";
    EXPECT_EQ(t[2].texels, data);
}

// A plugin built against ABI 1.0 passes the shorter AcetatePassDesc: accepted, and the 1.1
// fields past its end (here garbage that would be refused) are never read.
TEST(EffectGraph, AnAbi10SizedPassIsAccepted) {
    Fake fake;
    auto graph = fake.build([](Host& h) {
        h.pass({.inputs = {"previous", "mask.shadow"},
                .input_names = {"gl_bad", "gl_bad"},
                .defines = "not a define",
                .struct_size = offsetof(AcetatePassDesc, input_names)});
    });
    ASSERT_TRUE(graph) << graph.error().message;
    EXPECT_EQ(graph.value().passes[0].input_names,
              (std::vector<std::string>{"previous", "mask_shadow"}));
    EXPECT_EQ(graph.value().passes[0].defines, "");
}

TEST(EffectGraph, OnlyTheFirstRefusalIsReported) {
    Fake fake;
    EXPECT_EQ(refusal(fake.build([](Host& h) { h.target("Bad").pass({.blend = 9}); })),
              at("target \"Bad\": " + kBadTarget));
}

TEST(EffectGraph, ABuildThatFailsIsRefusedWithItsLastError) {
    Fake fake;
    t_status = ACETATE_ERROR_FAILED;
    t_error = "the floor has no water mask to work with";
    EXPECT_EQ(refusal(fake.build([](Host& h) { h.pass({}); })),
              at("build failed with status 1: the floor has no water mask to work with"));
    t_status = ACETATE_ERROR_EXCEPTION;
    t_error = nullptr;
    EXPECT_EQ(refusal(fake.build([](Host&) {})), at("build failed with status 5: (no message)"));
}

TEST(EffectGraph, ABuildWithNoPassWritingResultIsRefused) {
    Fake fake;
    EXPECT_EQ(refusal(fake.build([](Host& h) { h.target("a").pass({.output = "a"}); })),
              at("no pass writes \"result\""));
}

// Instanced quads read their rects from floor_data, which build() may set after the pass: the
// check runs once build() has returned.
TEST(EffectGraph, InstancedRectsMustLieWithinFloorData) {
    auto sparks = [](uint32_t floats) {
        return [floats](Host& h) {
            h.pass({.name = "copy"})
                .pass({.name = "sparks",
                       .blend = kAdd,
                       .kind = kQuads,
                       .instance_count = 2,
                       .instance_data_offset = 1})
                .floor_data(std::vector<float>(floats, 1.0f));
        };
    };
    Fake fake;
    EXPECT_EQ(refusal(fake.build(sparks(8))),
              pass_at("sparks",
                      " draws 2 quads whose rects end at floor_data[9], but floor_data "
                      "has 8 floats"));
    auto fits = fake.build(sparks(9));
    ASSERT_TRUE(fits) << fits.error().message;
    EXPECT_EQ(fits.value().passes[1].instance_data_offset, 1u);
}

// ---- 1.1 ----

TEST(EffectGraph, TargetFormatsAreRecordedAndCheckedAgainstTheDevice) {
    Fake fake;
    std::vector<std::pair<uint32_t, bool>> asked;
    fake.context.format_problem = [&](uint32_t format, bool blend) -> std::string {
        asked.emplace_back(format, blend);
        if (format == ACETATE_FORMAT_R32F) return "cannot be rendered to on this device";
        if (format == ACETATE_FORMAT_RG32F && blend) return "cannot be blended on this device";
        return "";
    };
    auto graph = fake.build([](Host& h) {
        h.target_info("half", kRG16F, 2)
            .target_info("plain", ACETATE_FORMAT_FLOOR)
            .target_info("wide", ACETATE_FORMAT_RG32F)
            .pass({.name = "fill", .output = "wide"})  // REPLACE onto RG32F: fine
            .pass({.name = "half", .output = "half"})
            .pass({.name = "more", .output = "half", .blend = kAdd})
            .pass({.inputs = {"half"}});
    });
    ASSERT_TRUE(graph) << graph.error().message;
    ASSERT_EQ(graph.value().targets.size(), 3u);
    EXPECT_EQ(graph.value().targets[0].format, kRG16F);
    EXPECT_EQ(graph.value().targets[0].divisor, 2u);
    EXPECT_EQ(graph.value().targets[1].format, ACETATE_FORMAT_FLOOR);
    EXPECT_EQ(graph.value().targets[2].format, ACETATE_FORMAT_RG32F);
    // FLOOR is never asked about, nor a REPLACE pass; a blending pass asks (format, true).
    EXPECT_EQ(asked, (std::vector<std::pair<uint32_t, bool>>{
                         {kRG16F, false}, {ACETATE_FORMAT_RG32F, false}, {kRG16F, true}}));

    EXPECT_EQ(refusal(fake.build([](Host& h) { h.target_info("deep", ACETATE_FORMAT_R32F); })),
              at("target \"deep\": format R32F cannot be rendered to on this device"));
    EXPECT_EQ(t_last, ACETATE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(refusal(fake.build([](Host& h) {
                  h.target_info("wide", ACETATE_FORMAT_RG32F)
                      .pass({.name = "fill", .output = "wide"})
                      .pass({.name = "glow", .output = "wide", .blend = kOver});
              })),
              pass_at("glow",
                      " blends onto \"wide\": format RG32F cannot be blended on this "
                      "device"));
    EXPECT_EQ(t_last, ACETATE_ERROR_INVALID_ARGUMENT);
}

TEST(EffectGraph, ReadMaskGivesTheFloorsCompositeOrZerosNeverNull) {
    FloorMasks masks;
    masks["water"] = ImageRGBA(3, 2);
    Fake fake;
    fake.context.masks = &masks;
    AcetateMaskImage water = mask_image(), shadow = mask_image(), again = mask_image();
    std::vector<float> zeros;
    auto graph = fake.build([&](Host& h) {
        h.mask("water", &water).mask("shadow", &shadow).mask("shadow", &again).pass({});
        // Only while build() runs: the canvas-sized zeros for "shadow", which this floor lacks.
        if (shadow.data) zeros.assign(shadow.data, shadow.data + 8 * 6 * 4);
    });
    ASSERT_TRUE(graph) << graph.error().message;
    EXPECT_EQ(water.data, masks["water"].pixels.data());
    EXPECT_EQ(std::vector<uint32_t>({water.width, water.height, water.channels}),
              std::vector<uint32_t>({3, 2, 4}));
    EXPECT_EQ(std::vector<uint32_t>({shadow.width, shadow.height, shadow.channels}),
              std::vector<uint32_t>({8, 6, 4}));  // the canvas
    EXPECT_NE(shadow.data, nullptr);
    EXPECT_EQ(again.data, shadow.data);
    EXPECT_EQ(zeros, std::vector<float>(8 * 6 * 4, 0.0f));

    // No masks at all (GraphContext::masks null): still zeros, never NULL.
    Fake bare;
    AcetateMaskImage m = mask_image();
    auto built = bare.build([&](Host& h) { h.mask("water", &m).pass({}); });
    ASSERT_TRUE(built) << built.error().message;
    EXPECT_NE(m.data, nullptr);
    EXPECT_EQ(m.width * m.height, 8u * 6u);
}

TEST(EffectGraph, AnExpandingEffectsReachIsRecorded) {
    Fake fake(ACETATE_COVERAGE_EXPANDING);
    auto graph = fake.build([](Host& h) { h.reach(16384).reach(12).pass({}); });
    ASSERT_TRUE(graph) << graph.error().message;
    EXPECT_EQ(graph.value().reach, 12u);
}

TEST(EffectGraph, PhasesAreRecorded) {
    Fake fake;
    auto graph = fake.build([](Host& h) {
        for (int i = 0; i < 63; ++i) h.phase(("p" + std::to_string(i)).c_str(), 1);
        h.phase("year", 3.15576e7).pass({});  // the 64th
    });
    ASSERT_TRUE(graph) << graph.error().message;
    ASSERT_EQ(graph.value().phases.size(), 64u);
    EXPECT_EQ(graph.value().phases[63].name, "year");
    EXPECT_EQ(graph.value().phases[63].period, 3.15576e7);
}

TEST(EffectGraph, InputNamesAndDefinesAreRecorded) {
    Fake fake;
    auto graph = fake.build([](Host& h) {
        h.texture("ramp", 1, 1)
            .pass({.inputs = {"previous", "mask.water", "texture.ramp"},
                   .input_names = {"source", nullptr, "lut_2"},
                   .defines = "#define GAIN 2\n\n#define TAPS 4"});
    });
    ASSERT_TRUE(graph) << graph.error().message;
    const GraphPass& p = graph.value().passes[0];
    EXPECT_EQ(p.input_names, (std::vector<std::string>{"source", "mask_water", "lut_2"}));
    EXPECT_EQ(p.defines, "#define GAIN 2\n\n#define TAPS 4\n");  // newline-terminated
}

}  // namespace
}  // namespace acetate::fake
