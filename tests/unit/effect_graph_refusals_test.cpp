// Every refusal of the effect graph's host functions, without a GPU: an in-process fake plugin (no
// shared library, no Vulkan device) declares targets, passes, textures and floor data through the
// AcetateHostApi, and every refusal the host makes is checked as the exact one-line message naming
// the instance, pass and resource -- the same checks tests/gpu/plugin_abi_test.cpp proves through a
// device.

#include "fake_plugin.hpp"

namespace acetate::fake {
namespace {

// ---- Every refusal of a host function, as a table. ----

struct RefusalCase {
    const char* name;
    Body body;  // or one pass
    std::string message;
    uint32_t coverage = ACETATE_COVERAGE_PRESERVING;

    RefusalCase(const char* n, Body b, std::string m, uint32_t c = ACETATE_COVERAGE_PRESERVING)
        : name(n), body(std::move(b)), message(std::move(m)), coverage(c) {}
    RefusalCase(const char* n, Pass p, std::string m)
        : RefusalCase(
              n, [p](Host& h) { h.pass(p); }, std::move(m)) {}
};

void PrintTo(const RefusalCase& c, std::ostream* os) {
    *os << c.name;
}

class Refusal : public ::testing::TestWithParam<RefusalCase> {};

TEST_P(Refusal, IsRefusedWithOneLineNamingTheResource) {
    const RefusalCase& c = GetParam();
    Fake fake(c.coverage);
    EXPECT_EQ(refusal(fake.build(c.body)), c.message);
    EXPECT_EQ(t_last, ACETATE_ERROR_INVALID_ARGUMENT) << "the refused call's own status";
}

const std::string kPassName = ": name must match [a-z][a-z0-9_]*";
const std::string kOneOf = ": give exactly one of glsl (non-empty) and spirv";
const std::string kNotSpirv = ": spirv is not a SPIR-V module (bad magic number or too short)";
const std::string kReserved =
    " is not a name [a-z][a-z0-9_]* free for the plugin (not gl_, acetate, param_ or phase_; no "
    "__)";

INSTANTIATE_TEST_SUITE_P(
    EffectGraph, Refusal,
    ::testing::Values(
        // declare_target
        RefusalCase{"TargetBadName", [](Host& h) { h.target("Bad"); },
                    at("target \"Bad\": " + kBadTarget)},
        RefusalCase{"TargetPrevious", [](Host& h) { h.target("previous"); },
                    at("target \"previous\": " + kBadTarget)},
        RefusalCase{"TargetResult", [](Host& h) { h.target("result"); },
                    at("target \"result\": " + kBadTarget)},
        RefusalCase{"TargetNoName", [](Host& h) { h.target(nullptr); },
                    at("declare_target with no name")},
        RefusalCase{"TargetTwice", [](Host& h) { h.target("t").target("t", 2); },
                    at("target \"t\" is declared twice")},
        RefusalCase{"DivisorThree", [](Host& h) { h.target("t", 3); },
                    at("target \"t\": divisor 3 is not a power of two between 1 and 4096")},
        RefusalCase{"DivisorZero", [](Host& h) { h.target("t", 0); },
                    at("target \"t\": divisor 0 is not a power of two between 1 and 4096")},
        RefusalCase{"DivisorAbove4096", [](Host& h) { h.target("t", 8192); },
                    at("target \"t\": divisor 8192 is not a power of two between 1 and 4096")},
        // add_pass
        RefusalCase{"PassShortStruct", Pass{.struct_size = offsetof(AcetatePassDesc, input_names) - 4},
                    at("add_pass with a missing or short AcetatePassDesc")},
        RefusalCase{"PassBadName", Pass{.name = "Down"}, pass_at("Down", kPassName)},
        RefusalCase{"PassNoName", Pass{.name = nullptr}, pass_at("", kPassName)},
        RefusalCase{"PassTwice", [](Host& h) { h.pass({}).pass({}); },
                    pass_at("p", ": declared twice")},
        RefusalCase{"PassUnknownKind", Pass{.kind = 2}, pass_at("p", ": unknown kind 2")},
        RefusalCase{"InstanceCountZero", Pass{.kind = kQuads, .instance_count = 0},
                    pass_at("p", ": instance_count 0 is not in 1..1048576")},
        RefusalCase{"InstanceCountTooMany", Pass{.kind = kQuads, .instance_count = 1048577},
                    pass_at("p", ": instance_count 1048577 is not in 1..1048576")},
        RefusalCase{"GlslAndSpirv", Pass{.spirv = kSpirv}, pass_at("p", kOneOf)},
        RefusalCase{"NeitherGlslNorSpirv", Pass{.glsl = nullptr}, pass_at("p", kOneOf)},
        RefusalCase{"EmptyGlsl", Pass{.glsl = ""}, pass_at("p", kOneOf)},
        RefusalCase{"SpirvBadMagic", Pass{.glsl = nullptr, .spirv = {0xdeadbeefu, 0, 0, 1, 0}},
                    pass_at("p", kNotSpirv)},
        RefusalCase{"SpirvTooShort", Pass{.glsl = nullptr, .spirv = {0x07230203u, 0, 0, 1}},
                    pass_at("p", kNotSpirv)},
        RefusalCase{"NineInputs", Pass{.inputs = std::vector<const char*>(9, "previous")},
                    pass_at("p", ": 9 inputs (at most 8, and inputs must not be NULL)")},
        RefusalCase{"UnknownBlend", Pass{.blend = 3}, pass_at("p", ": unknown blend 3")},
        RefusalCase{"UndeclaredMaskKind", Pass{.inputs = {"mask.lava"}},
                    pass_at("p", " reads \"mask.lava\", a mask kind the descriptor does not "
                                 "list in masks")},
        RefusalCase{"UndeclaredTexture", Pass{.inputs = {"texture.ramp"}},
                    pass_at("p", " reads \"texture.ramp\", which add_texture has not declared")},
        RefusalCase{"UnknownInputTarget", Pass{.inputs = {"nowhere"}},
                    pass_at("p", " reads \"nowhere\", which is neither \"previous\", a mask nor "
                                 "a declared target")},
        RefusalCase{"ReadsUnwrittenTarget",
                    [](Host& h) {
                        h.target("blurred", 2).pass(
                            {.name = "combine", .inputs = {"previous", "blurred"}});
                    },
                    pass_at("combine", " reads \"blurred\", which no earlier pass writes")},
        RefusalCase{"ReadsAnInputTwice", Pass{.inputs = {"previous", "previous"}},
                    pass_at("p", " reads \"previous\" twice")},
        RefusalCase{"WritesUnknownOutput", Pass{.output = "nowhere"},
                    pass_at("p", " writes \"nowhere\", which is neither \"result\" nor a "
                                 "declared target")},
        RefusalCase{"ReadsAndWritesOneTarget",
                    [](Host& h) {
                        h.target("a").pass({.output = "a"}).pass(
                            {.name = "q", .inputs = {"a"}, .output = "a"});
                    },
                    pass_at("q", " reads and writes \"a\"")},
        RefusalCase{"AddBeforeReplace",
                    [](Host& h) { h.target("a").pass({.output = "a", .blend = kAdd}); },
                    pass_at("p", " blends onto \"a\" before any full-size pass replaced it")},
        RefusalCase{"OverBeforeReplace", Pass{.blend = ACETATE_BLEND_OVER},
                    pass_at("p", " blends onto \"result\" before any full-size pass replaced it")},
        RefusalCase{"InstancedBeforeReplace",
                    [](Host& h) {
                        h.floor_data({0, 0, 1, 1}).pass({.kind = kQuads, .instance_count = 1});
                    },
                    pass_at("p", " blends onto \"result\" before any full-size pass replaced it")},
        // set_floor_data
        RefusalCase{"FloorDataTooMany", [](Host& h) { h.floor_data(&kOne, 1048577); },
                    at("set_floor_data with 1048577 floats (at most 1048576, data not NULL)")},
        RefusalCase{"FloorDataNull", [](Host& h) { h.floor_data(nullptr, 1); },
                    at("set_floor_data with 1 floats (at most 1048576, data not NULL)")},
        RefusalCase{"FloorDataNaN", [](Host& h) { h.floor_data({1.0f, kNaN}); },
                    at("set_floor_data: a value is not finite")},
        // add_texture, add_texture_info
        RefusalCase{"TextureBadName", [](Host& h) { h.texture("Ramp", 1, 1); },
                    at("texture \"Ramp\": name must match [a-z][a-z0-9_]*")},
        RefusalCase{"TextureNoName", [](Host& h) { h.texture(nullptr, 1, 1); },
                    at("add_texture with no name")},
        RefusalCase{"TextureTwice", [](Host& h) { h.texture("ramp", 2, 1).texture("ramp", 2, 1); },
                    at("texture \"ramp\": declared twice")},
        RefusalCase{"TextureZeroWidth", [](Host& h) { h.texture("ramp", 0, 1); },
                    at("texture \"ramp\": 0x1 (1..16384 per side, data not NULL)")},
        RefusalCase{"TextureTooTall", [](Host& h) { h.texture("ramp", 1, 16385); },
                    at("texture \"ramp\": 1x16385 (1..16384 per side, data not NULL)")},
        RefusalCase{"TextureNaN", [](Host& h) { h.texture("ramp", 2, 2, kNaN); },
                    at("texture \"ramp\": holds a value that is not finite")},
        RefusalCase{"TextureInfoShort",
                    [](Host& h) {
                        const AcetateTextureInfo t{offsetof(AcetateTextureInfo, rgba), "ramp", 1,
                                                   1, &kOne, 0};
                        h.note(h.api->add_texture_info(h.graph, &t));
                    },
                    at("add_texture_info with a missing or short AcetateTextureInfo")},
        RefusalCase{"TextureInfoUnknownFormat",
                    [](Host& h) {
                        const AcetateTextureInfo t{sizeof(AcetateTextureInfo), "ramp", 1, 1, &kOne,
                                                   9};
                        h.note(h.api->add_texture_format(h.graph, &t));
                    },
                    at("texture \"ramp\": unknown format 9")},
        RefusalCase{"TextureFormatShort",
                    [](Host& h) {
                        const AcetateTextureInfo t{offsetof(AcetateTextureInfo, format), "ramp", 1,
                                                   1, &kOne, 0};
                        h.note(h.api->add_texture_format(h.graph, &t));
                    },
                    at("add_texture_format with a missing or short AcetateTextureInfo")},
        // 1.1: declare_target_info
        RefusalCase{"TargetInfoUnknownFormat", [](Host& h) { h.target_info("t", 7); },
                    at("target \"t\": unknown format 7")},
        RefusalCase{"TargetInfoShort", [](Host& h) { h.target_info("t", kRG16F, 1, 8); },
                    at("declare_target_info with a missing or short AcetateTargetInfo")},
        RefusalCase{"TargetInfoTwice", [](Host& h) { h.target("t").target_info("t", kRG16F); },
                    at("target \"t\" is declared twice")},
        // 1.1: read_mask
        RefusalCase{"ReadMaskUndeclaredKind",
                    [](Host& h) { h.mask("lava", sizeof(AcetateMaskImage)); },
                    at("read_mask(\"lava\"): a mask kind the descriptor does not list in masks")},
        RefusalCase{"ReadMaskShortStruct",
                    [](Host& h) { h.mask("water", offsetof(AcetateMaskImage, data)); },
                    at("read_mask(\"water\") with a missing or short AcetateMaskImage")},
        RefusalCase{"ReadMaskNull", [](Host& h) { h.mask("water", nullptr); },
                    at("read_mask(\"water\") with a missing or short AcetateMaskImage")},
        // 1.1: set_reach
        RefusalCase{"ReachOfAPreservingEffect", [](Host& h) { h.reach(12); },
                    at("set_reach(12): only a coverage-expanding effect has a reach")},
        RefusalCase{"ReachAbove16384", [](Host& h) { h.reach(16385); },
                    at("set_reach(16385): at most 16384 pixels"), ACETATE_COVERAGE_EXPANDING},
        // 1.1: declare_phase
        RefusalCase{"PhaseBadName", [](Host& h) { h.phase("Spin", 1); },
                    at("phase \"Spin\": name must match [a-z][a-z0-9_]*")},
        RefusalCase{"PhaseTwice", [](Host& h) { h.phase("spin", 1).phase("spin", 2); },
                    at("phase \"spin\": declared twice")},
        RefusalCase{"PhasePeriodZero", [](Host& h) { h.phase("spin", 0); },
                    at("phase \"spin\": period 0 s is not a finite number of at least 1e-6 s")},
        RefusalCase{"PhasePeriodNegative", [](Host& h) { h.phase("spin", -2.5); },
                    at("phase \"spin\": period -2.5 s is not a finite number of at least 1e-6 s")},
        RefusalCase{"PhasePeriodNaN", [](Host& h) { h.phase("spin", std::nan("")); },
                    at("phase \"spin\": period nan s is not a finite number of at least 1e-6 s")},
        RefusalCase{"PhasePeriodInf", [](Host& h) { h.phase("spin", kInf); },
                    at("phase \"spin\": period inf s is not a finite number of at least 1e-6 s")},
        RefusalCase{"The65thPhase",
                    [](Host& h) {
                        for (int i = 0; i < 64; ++i) h.phase(("p" + std::to_string(i)).c_str(), 1);
                        h.phase("p64", 1);
                    },
                    at("phase \"p64\": at most 64 phases")},
        // 1.1: input_names, defines
        RefusalCase{"InputNameAcetate", Pass{.input_names = {"acetate_x"}},
                    pass_at("p", ": input_names[0] \"acetate_x\"" + kReserved)},
        RefusalCase{"InputNameGl", Pass{.input_names = {"gl_x"}},
                    pass_at("p", ": input_names[0] \"gl_x\"" + kReserved)},
        RefusalCase{"InputNameParam",
                    Pass{.inputs = {"previous", "mask.water"}, .input_names = {nullptr, "param_x"}},
                    pass_at("p", ": input_names[1] \"param_x\"" + kReserved)},
        RefusalCase{"InputNamePhase", Pass{.input_names = {"phase_x"}},
                    pass_at("p", ": input_names[0] \"phase_x\"" + kReserved)},
        RefusalCase{"InputNameNotAnIdentifier", Pass{.input_names = {"2nd"}},
                    pass_at("p", ": input_names[0] \"2nd\"" + kReserved)},
        RefusalCase{"InputNameHostStruct", Pass{.input_names = {"AcetateLight"}},
                    pass_at("p", ": input_names[0] \"AcetateLight\"" + kReserved)},
        RefusalCase{"InputNameDoubleUnderscore", Pass{.input_names = {"a__b"}},
                    pass_at("p", ": input_names[0] \"a__b\"" + kReserved)},
        RefusalCase{"InputNameOutColor", Pass{.input_names = {"out_color"}},
                    pass_at("p", ": input_names[0] \"out_color\"" + kReserved)},
        RefusalCase{"TwoInputsOneGlslName",
                    Pass{.inputs = {"previous", "mask.water"}, .input_names = {"mask_water", nullptr}},
                    pass_at("p", ": two inputs are named \"mask_water\" in GLSL")},
        RefusalCase{"DefaultGlslNamesCollide",
                    [](Host& h) {
                        h.target("mask_water")
                            .pass({.name = "fill", .output = "mask_water"})
                            .pass({.inputs = {"mask.water", "mask_water"}});
                    },
                    pass_at("p", ": two inputs are named \"mask_water\" in GLSL")},
        RefusalCase{"DefineLineNotADefine", Pass{.defines = "#define GAIN 2\n\nint x;\n"},
                    pass_at("p", ": defines line 3 is not a \"#define NAME VALUE\" line: "
                                 "\"int x;\"")}),
    [](const ::testing::TestParamInfo<RefusalCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace acetate::fake
