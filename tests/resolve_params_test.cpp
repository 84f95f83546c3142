// resolve_params without a GPU: the scene's values for an effect's parameters, checked and
// clamped, with one-line errors naming the scene field.

#include <gtest/gtest.h>

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

// A number beyond the float range is said to be out of range, not "not finite" (which is what
// it would look like after a conversion to float).
TEST(ResolveParams, ANumberBeyondTheFloatRangeIsNamedSo) {
    for (double huge : {-1e308, 1e39}) {
        auto values = resolve({{"radius", huge}});
        ASSERT_FALSE(values);
        EXPECT_EQ(values.error().code, ErrorCode::InvalidInput);
        EXPECT_EQ(values.error().message,
                  "scene.json: floors[0].effects[0].params.radius: " + nlohmann::json(huge).dump() +
                      " is out of range for a 32-bit float");
    }
}

}  // namespace
}  // namespace acetate
