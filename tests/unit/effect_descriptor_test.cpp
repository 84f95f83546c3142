// A plugin's descriptor without a GPU: copy_descriptor's ABI 1.1 checks (the minor version,
// vector and hidden parameters), and resolve_param_vectors reading vector parameters from the
// scene. Every refusal is checked as its exact one-line message.

#include "plugins/effect_descriptor.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "plugins/resolve_params.hpp"

namespace acetate {
namespace {

// A 1.1 descriptor "test.fake" whose parameters are `params`, extended by `exts` (one pointer
// per parameter, or none).
struct Descriptor {
    std::vector<AcetateParamDesc> params;
    std::vector<const AcetateParamExt*> exts;
    std::vector<AcetatePresetValue> preset_values;
    AcetatePresetDesc preset{"low", nullptr, 0};
    AcetateEffectDescriptor d{};

    Descriptor() {
        d.struct_size = sizeof d;
        d.abi_version = ACETATE_ABI_VERSION;
        d.id = "test.fake";
        d.abi_minor = ACETATE_ABI_MINOR;
    }
    Result<EffectDescriptor> copy() {
        d.params = params.data();
        d.param_count = uint32_t(params.size());
        d.param_exts = exts.empty() ? nullptr : exts.data();
        preset.values = preset_values.data();
        preset.value_count = uint32_t(preset_values.size());
        d.presets = preset_values.empty() ? nullptr : &preset;
        d.preset_count = preset_values.empty() ? 0 : 1;
        return copy_descriptor(&d, "fake.so");
    }
};

std::string refusal(const Result<EffectDescriptor>& copied) {
    if (copied.ok()) return "(accepted)";
    EXPECT_EQ(copied.error().code, ErrorCode::InvalidInput);
    return copied.error().message;
}

const AcetateParamExt kOffsetExt{sizeof(AcetateParamExt), 0, {1, -2, 0, 0}};
const AcetateParamDesc kOffset{"offset", "a shift", ACETATE_PARAM_VEC2, 1, -10, 10};

TEST(EffectDescriptor, APluginBuiltForANewerMinorIsRefusedNamingBothVersions) {
    Descriptor fake;
    fake.d.abi_minor = ACETATE_ABI_MINOR + 1;
    EXPECT_EQ(refusal(fake.copy()),
              "fake.so: built for Acetate ABI 1.3; this host supports ABI 1.2");
}

// scale_tolerance is read when the descriptor reaches it, bounded, and 0 for a descriptor
// that ends before it (one built before the field, with whatever lies past its end).
TEST(EffectDescriptor, AScaleToleranceIsReadWhenPresentAndBounded) {
    Descriptor fake;
    fake.d.scale_tolerance = 0.25f;
    auto copied = fake.copy();
    ASSERT_TRUE(copied) << copied.error().message;
    EXPECT_EQ(copied.value().scale_tolerance, 0.25f);

    for (const float bad : {-0.5f, 4.5f, NAN, INFINITY}) {
        fake.d.scale_tolerance = bad;
        EXPECT_EQ(refusal(fake.copy()),
                  fmt::format("fake.so: descriptor: scale_tolerance {} is not a number from 0 "
                              "to 4",
                              bad));
    }
    fake.d.scale_tolerance = 0.25f;

    fake.d.struct_size = offsetof(AcetateEffectDescriptor, scale_tolerance);
    copied = fake.copy();
    ASSERT_TRUE(copied) << copied.error().message;
    EXPECT_EQ(copied.value().scale_tolerance, 0.0f);
}

// A plugin built against 1.0 has the shorter descriptor: accepted as minor 0, and nothing past
// its end (here a newer abi_minor and garbage param_exts) is read.
TEST(EffectDescriptor, AnAbi10SizedDescriptorIsAcceptedAsMinor0) {
    Descriptor fake;
    fake.d.struct_size = offsetof(AcetateEffectDescriptor, abi_minor);
    fake.d.abi_minor = 7;
    fake.params = {{"strength", "how much", ACETATE_PARAM_FLOAT, 0.5f, 0, 1}};
    fake.exts = {reinterpret_cast<const AcetateParamExt*>(alignof(AcetateParamExt))};
    auto copied = fake.copy();
    ASSERT_TRUE(copied) << copied.error().message;
    EXPECT_EQ(copied.value().abi_minor, 0u);
    EXPECT_FALSE(copied.value().params[0].hidden);
    EXPECT_EQ(copied.value().params[0].default_vector, (std::array<float, 4>{0.5f, 0, 0, 0}));

    // ... and a 1.0 descriptor cannot declare the 1.1 parameter types.
    fake.exts.clear();
    fake.params = {kOffset};
    EXPECT_EQ(refusal(fake.copy()), "fake.so: descriptor: params[0] \"offset\": unknown type 3");
}

TEST(EffectDescriptor, VectorParamsAreRecordedWithTheirDefaults) {
    // Fractional defaults: a vector is not an int/bool parameter.
    const AcetateParamExt tint{sizeof(AcetateParamExt), 0, {0.5f, 0.25f, 0.125f, 9}};
    const AcetateParamExt axis{sizeof(AcetateParamExt), 0, {0, 0, 1, 9}};
    Descriptor fake;
    fake.params = {kOffset,
                   {"tint", "linear RGB", ACETATE_PARAM_COLOR, 0.5f, 0, 1},
                   {"axis", "a direction", ACETATE_PARAM_VEC3, 0, -1, 1},
                   {"gain", "a scalar", ACETATE_PARAM_FLOAT, 2, 0, 4}};
    fake.exts = {&kOffsetExt, &tint, &axis, nullptr};
    auto copied = fake.copy();
    ASSERT_TRUE(copied) << copied.error().message;
    const auto& p = copied.value().params;
    EXPECT_EQ(p[0].components(), 2u);
    EXPECT_EQ(p[0].default_vector, (std::array<float, 4>{1, -2, 0, 0}));
    EXPECT_EQ(p[1].components(), 3u);
    EXPECT_EQ(p[1].default_vector, (std::array<float, 4>{0.5f, 0.25f, 0.125f, 0}));  // w dropped
    EXPECT_EQ(p[2].default_vector, (std::array<float, 4>{0, 0, 1, 0}));
    EXPECT_EQ(p[3].components(), 1u);
    EXPECT_EQ(p[3].default_vector, (std::array<float, 4>{2, 0, 0, 0}));
}

TEST(EffectDescriptor, AVectorParamNeedsItsExtension) {
    const std::string message =
        "fake.so: descriptor: params[0] \"offset\": a vector parameter needs param_exts[0] for "
        "its default";
    Descriptor fake;
    fake.params = {kOffset};
    EXPECT_EQ(refusal(fake.copy()), message);  // param_exts NULL
    fake.exts = {nullptr};
    EXPECT_EQ(refusal(fake.copy()), message);  // its own entry NULL
    const AcetateParamExt shorter{8, 0, {1, -2, 0, 0}};
    fake.exts = {&shorter};
    EXPECT_EQ(refusal(fake.copy()),
              "fake.so: descriptor: params[0] \"offset\": param_exts[0].struct_size 8 is too "
              "small");
}

TEST(EffectDescriptor, AVectorDefaultIsCheckedAgainstTheRange) {
    Descriptor fake;
    fake.params = {kOffset};
    const AcetateParamExt differs{sizeof(AcetateParamExt), 0, {2, 0, 0, 0}};
    fake.exts = {&differs};
    EXPECT_EQ(refusal(fake.copy()),
              "fake.so: descriptor: params[0] \"offset\": default_value 1 differs from "
              "default_vector[0] 2");
    const AcetateParamExt outside{sizeof(AcetateParamExt), 0, {1, 20, 0, 0}};
    fake.exts = {&outside};
    EXPECT_EQ(refusal(fake.copy()),
              "fake.so: descriptor: params[0] \"offset\": default component 1 = 20 is outside "
              "[-10, 10]");
    fake.params[0].default_value = 11;
    const AcetateParamExt first_outside{sizeof(AcetateParamExt), 0, {11, 0, 0, 0}};
    fake.exts = {&first_outside};
    EXPECT_EQ(refusal(fake.copy()),
              "fake.so: descriptor: params[0] \"offset\": default 11 is outside [-10, 10]");
}

TEST(EffectDescriptor, APresetCannotSetAVectorParam) {
    Descriptor fake;
    fake.params = {kOffset};
    fake.exts = {&kOffsetExt};
    fake.preset_values = {{"offset", 1}};
    EXPECT_EQ(refusal(fake.copy()),
              "fake.so: descriptor: presets[0] \"low\": \"offset\" is a vector parameter; presets "
              "set scalar parameters only");
}

// A preset may have any name a scene file and a command line can carry, and the order the
// plugin declared its presets in is kept (the bench's reference is the last).
TEST(EffectDescriptor, PresetNamesAreAnyShortLowerCaseWord) {
    Descriptor fake;
    fake.params = {{"taps", "a quality knob", ACETATE_PARAM_INT, 4, 1, 16}};
    fake.preset_values = {{"taps", 2}};
    for (const char* name : {"low", "draft", "print-300dpi", "x_2"}) {
        fake.preset.name = name;
        auto copied = fake.copy();
        ASSERT_TRUE(copied) << name << ": " << copied.error().message;
        EXPECT_EQ(copied.value().preset_order, std::vector<std::string>{name});
    }
    const std::string too_long(33, 'a');
    for (const std::string& name : {std::string(), std::string("Ultra"), std::string("2x"),
                                    std::string("very fine"), too_long}) {
        fake.preset.name = name.c_str();
        EXPECT_EQ(refusal(fake.copy()),
                  "fake.so: descriptor: presets[0] \"" + name +
                      "\": a preset's name is 1 to 32 lower-case letters, digits, '-' or '_', "
                      "starting with a letter")
            << name;
    }
}

TEST(EffectDescriptor, HiddenIsRecordedAndUnknownFlagsAreRefused) {
    const AcetateParamExt hidden{sizeof(AcetateParamExt), ACETATE_PARAM_HIDDEN, {}};
    Descriptor fake;
    fake.params = {{"taps", "a quality knob", ACETATE_PARAM_INT, 4, 1, 16},
                   {"gain", "a scalar", ACETATE_PARAM_FLOAT, 2, 0, 4}};
    fake.exts = {&hidden, nullptr};
    fake.preset_values = {{"taps", 2}};
    auto copied = fake.copy();
    ASSERT_TRUE(copied) << copied.error().message;
    EXPECT_TRUE(copied.value().params[0].hidden);
    EXPECT_FALSE(copied.value().params[1].hidden);
    EXPECT_EQ(copied.value().presets.at("low").at("taps"), 2.0f);

    const AcetateParamExt unknown{sizeof(AcetateParamExt), ACETATE_PARAM_HIDDEN | 2u, {}};
    fake.exts = {&unknown, nullptr};
    EXPECT_EQ(refusal(fake.copy()), "fake.so: descriptor: params[0] \"taps\": unknown flags 0x3");
}

// ---- resolve_param_vectors: the scene's values for vector and hidden parameters. ----

EffectDescriptor vector_params() {
    EffectDescriptor d;
    d.id = "com.example.test";
    EffectParam offset{"offset", "a shift", ACETATE_PARAM_VEC2, 1, -10, 10};
    offset.default_vector = {1, -2, 0, 0};
    EffectParam tint{"tint", "linear RGB", ACETATE_PARAM_COLOR, 1, 0, 1};
    tint.default_vector = {1, 0.5f, 0.25f, 0};
    EffectParam taps{"taps", "a quality knob", ACETATE_PARAM_INT, 4, 1, 16};
    taps.hidden = true;
    taps.default_vector = {4, 0, 0, 0};
    d.params = {offset, tint, taps};
    d.presets["low"] = {{"taps", 2.0f}};
    return d;
}

Result<ParamVectors> resolve(const nlohmann::json& params, const std::string& preset = "") {
    EffectRef ref;
    ref.plugin = "com.example.test";
    ref.params = params;
    ref.preset = preset;
    ref.where = "floors[0].effects[0]";
    return resolve_param_vectors(vector_params(), ref, "scene.json");
}

using Vec = std::array<float, 4>;

TEST(ResolveParamVectors, DefaultsAndPresetsFillEveryComponent) {
    auto values = resolve(nlohmann::json::object(), "low");
    ASSERT_TRUE(values) << values.error().message;
    EXPECT_EQ(values.value(),
              (ParamVectors{Vec{1, -2, 0, 0}, Vec{1, 0.5f, 0.25f, 0}, Vec{2, 0, 0, 0}}));
}

TEST(ResolveParamVectors, AVectorFromAJsonArrayIsClampedPerComponent) {
    auto values = resolve({{"offset", {25, -3.5}}, {"tint", {0.5, -1, 2}}});
    ASSERT_TRUE(values) << values.error().message;
    EXPECT_EQ(values.value()[0], (Vec{10, -3.5f, 0, 0}));
    EXPECT_EQ(values.value()[1], (Vec{0.5f, 0, 1, 0}));
    // The scalar view (ABI 1.0's params) is each parameter's x.
    EffectRef ref;
    ref.params = {{"offset", {-25, 0}}};
    ref.where = "floors[0].effects[0]";
    auto scalars = resolve_params(vector_params(), ref, "scene.json");
    ASSERT_TRUE(scalars) << scalars.error().message;
    EXPECT_EQ(scalars.value(), (std::vector<float>{-10, 1, 4}));
}

TEST(ResolveParamVectors, AWrongArrayIsRefused) {
    const std::string field = "scene.json: floors[0].effects[0].params.";
    auto refused = [](const nlohmann::json& params) {
        auto values = resolve(params);
        return values ? std::string("(accepted)") : values.error().message;
    };
    EXPECT_EQ(refused({{"offset", {1, 2, 3}}}),
              field + "offset: expected an array of 2 numbers, got [1,2,3]");
    EXPECT_EQ(refused({{"tint", {1, 2}}}),
              field + "tint: expected an array of 3 numbers, got [1,2]");
    EXPECT_EQ(refused({{"offset", 1}}), field + "offset: expected an array of 2 numbers, got 1");
    EXPECT_EQ(refused({{"offset", {1, "x"}}}), field + "offset[1]: expected a number, got \"x\"");
}

TEST(ResolveParamVectors, AHiddenParamSetByTheSceneIsRefused) {
    auto values = resolve({{"taps", 8}});
    ASSERT_FALSE(values);
    EXPECT_EQ(values.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(values.error().message,
              "scene.json: floors[0].effects[0].params.taps: plugin \"com.example.test\" sets this "
              "parameter from its presets only; choose a preset instead");
    // Unknown names list only the parameters a scene may set.
    auto unknown = resolve({{"radius", 1}});
    ASSERT_FALSE(unknown);
    EXPECT_EQ(unknown.error().message,
              "scene.json: floors[0].effects[0].params.radius: plugin \"com.example.test\" has no "
              "such parameter (it has: offset, tint)");
}

}  // namespace
}  // namespace acetate
