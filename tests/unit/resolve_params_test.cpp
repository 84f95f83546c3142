// resolve_params without a GPU: the scene's values for an effect's parameters, checked and
// clamped, with one-line errors naming the scene field.

#include <gtest/gtest.h>

#include <tuple>

#include "render/effect_runtime.hpp"

namespace acetate {
namespace {

EffectDescriptor one_parameter() {
    EffectDescriptor d;
    d.id = "com.example.test";
    d.params.push_back({"radius", "how far", ACETATE_PARAM_FLOAT, 1.0f, 0.0f, 10.0f});
    d.params.push_back({"taps", "how many", ACETATE_PARAM_INT, 4.0f, 1.0f, 8.0f});
    return d;
}

Result<std::vector<float>> resolve(const nlohmann::json& params) {
    EffectRef ref;
    ref.plugin = "com.example.test";
    ref.params = params;
    ref.where = "floors[0].effects[0]";
    return resolve_params(one_parameter(), ref, "scene.json");
}

TEST(ResolveParams, ValuesAreClampedAndIntsRounded) {
    auto values = resolve({{"radius", 25.0}, {"taps", 4.6}});
    ASSERT_TRUE(values) << values.error().message;
    EXPECT_EQ(values.value(), (std::vector<float>{10.0f, 5.0f}));
}

// Any finite number is clamped to the parameter's range, as docs/scene-format.md says, even
// one beyond the 32-bit float range (1e39 was refused as "out of range" before the one reader of
// numbers): it is fitted in double, never turned into an infinity first.
TEST(ResolveParams, AFiniteNumberBeyondTheFloatRangeIsClampedAsDocumented) {
    for (auto [huge, radius, taps] : {std::tuple{1e39, 10.0f, 8.0f}, std::tuple{1e308, 10.0f, 8.0f},
                                      std::tuple{-1e308, 0.0f, 1.0f}}) {
        auto values = resolve({{"radius", huge}, {"taps", huge}});
        ASSERT_TRUE(values) << values.error().message;
        EXPECT_EQ(values.value(), (std::vector<float>{radius, taps})) << huge;
    }
}

EffectDescriptor vectors() {
    EffectDescriptor d;
    d.id = "com.example.test";
    EffectParam offset{"offset", "where", ACETATE_PARAM_VEC2, 0.0f, -4.0f, 4.0f};
    offset.default_vector = {0.0f, 0.0f, 0.0f, 0.0f};
    EffectParam tint{"tint", "colour", ACETATE_PARAM_COLOR, 1.0f, 0.0f, 1.0f};
    tint.default_vector = {1.0f, 1.0f, 1.0f, 0.0f};
    d.params = {offset, tint, {"on", "switch", ACETATE_PARAM_BOOL, 0.0f, 0.0f, 1.0f}};
    return d;
}

Result<ParamVectors> resolve_vectors(const nlohmann::json& params) {
    EffectRef ref;
    ref.plugin = "com.example.test";
    ref.params = params;
    ref.where = "floors[0].effects[0]";
    return resolve_param_vectors(vectors(), ref, "scene.json");
}

// A vector or colour parameter is "an array of exactly 2 or 3 numbers" (scene-format.md): a
// boolean component is refused, naming the component; a scalar still takes true/false.
TEST(ResolveParams, AVectorComponentMustBeANumber) {
    for (const char* name : {"offset", "tint"}) {
        nlohmann::json params;
        params[name] = std::string(name) == "offset" ? nlohmann::json{1, true}
                                                     : nlohmann::json{0.5, 0.5, false};
        auto values = resolve_vectors(params);
        ASSERT_FALSE(values) << name;
        EXPECT_EQ(values.error().message,
                  std::string("scene.json: floors[0].effects[0].params.") + name +
                      (std::string(name) == "offset" ? "[1]: expected a number, got true"
                                                     : "[2]: expected a number, got false"));
    }
    auto scalar = resolve_vectors({{"on", true}, {"offset", {1e39, -2}}, {"tint", {0.5, 2, 0}}});
    ASSERT_TRUE(scalar) << scalar.error().message;
    EXPECT_EQ(scalar.value()[2][0], 1.0f);
    EXPECT_EQ(scalar.value()[0][0], 4.0f);  // 1e39 clamped to the max, component by component
    EXPECT_EQ(scalar.value()[0][1], -2.0f);
    EXPECT_EQ(scalar.value()[1][1], 1.0f);
}

}  // namespace
}  // namespace acetate
