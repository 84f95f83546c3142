// The combined cases' design (harness/pairwise.hpp, harness/combinations.hpp): a covering array
// covers every pair of levels of every two factors, is the same for a seed, stays near the
// smallest possible size, and the factors are every dimension of the input model a plugin can
// observe, each component of a vector parameter apart, with every preset. No device.

#include "pairwise.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "combinations.hpp"
#include "input_model.hpp"

namespace acetate::harness {
namespace {

TEST(Pairwise, EveryPairOfLevelsIsCoveredAndTheSizeIsNearTheBound) {
    const std::vector<std::vector<int>> designs = {
        {2, 2}, {3, 3, 3, 3}, {12, 7, 6, 5, 4, 3, 3, 2, 2, 2, 3, 3, 3}, {1, 5, 2}, {4}};
    for (const std::vector<int>& levels : designs) {
        const CoveringArray a = pairwise_covering_array(levels, 7);
        EXPECT_EQ(uncovered_pairs(levels, a.rows), 0u);
        for (const std::vector<int>& row : a.rows) {
            ASSERT_EQ(row.size(), levels.size());
            for (size_t f = 0; f < row.size(); ++f) {
                EXPECT_GE(row[f], 0);
                EXPECT_LT(row[f], levels[f]);
            }
        }
        // No fewer rows than the two largest factors' product; a greedy design stays within a
        // quarter above it on these (AETG's own figures are of that order).
        std::vector<int> sorted = levels;
        std::sort(sorted.rbegin(), sorted.rend());
        const size_t bound = sorted.size() > 1 ? size_t(sorted[0] * sorted[1]) : size_t(sorted[0]);
        EXPECT_GE(a.rows.size(), bound);
        EXPECT_LE(a.rows.size(), bound + bound / 4 + 2);
    }
}

TEST(Pairwise, TheSameSeedGivesTheSameRowsAndAnotherSeedOthers) {
    const std::vector<int> levels = {5, 3, 6, 4, 12, 7, 5, 2, 2, 3, 2, 3, 3};
    EXPECT_EQ(pairwise_covering_array(levels, 1).rows, pairwise_covering_array(levels, 1).rows);
    EXPECT_NE(pairwise_covering_array(levels, 1).rows, pairwise_covering_array(levels, 2).rows);
}

TEST(Pairwise, AMissingRowLeavesPairsUncovered) {
    const std::vector<int> levels = {3, 3, 3};
    CoveringArray a = pairwise_covering_array(levels, 3);
    a.rows.pop_back();
    EXPECT_GT(uncovered_pairs(levels, a.rows), 0u);
}

PluginInfo plugin_with_everything() {
    PluginInfo p;
    p.id = "com.example.tint";
    p.scope = "floor";
    p.coverage = "preserving";
    p.masks = {"water"};
    p.params = {{"gain", "float", 1.0f, 0.0f, 2.0f, 1},
                {"tint", "color", 1.0f, 0.0f, 1.0f, 3},
                {"soft", "bool", 0.0f, 0.0f, 1.0f, 1}};
    p.presets = {"low", "high"};
    return p;
}

TEST(Combinations, EveryObservedDimensionIsAFactorAndEachComponentToo) {
    const PluginInfo plugin = plugin_with_everything();
    std::set<std::string> names;
    for (const CombinationFactor& f : combination_factors(plugin)) names.insert(f.name);
    for (const InputDimension& d : input_dimensions()) {
        // Per process; per parameter; a second render beside its own case (a relation).
        if (d.name == "poison" || d.name == "params" || d.name == "camera") continue;
        EXPECT_TRUE(names.count(d.name)) << d.name << " is not combined";
    }
    for (const char* param :
         {"params.gain", "params.tint[0]", "params.tint[1]", "params.tint[2]", "params.soft"})
        EXPECT_TRUE(names.count(param)) << param;
    EXPECT_TRUE(names.count("preset"));
}

TEST(Combinations, TheCasesSetEachComponentAndPresetTheDesignNames) {
    const PluginInfo plugin = plugin_with_everything();
    const Combinations c = pairwise_combinations(plugin, 5);
    ASSERT_FALSE(c.cases.empty());
    EXPECT_NE(c.summary.find("strength 2"), std::string::npos) << c.summary;
    // Every pair (preset, a tint component's level) is some case's: here, each preset meets
    // the first component at its minimum, and that component differs from the others somewhere.
    std::set<std::string> preset_with_min;
    bool components_apart = false;
    for (const CaseSpec& s : c.cases) {
        ASSERT_TRUE(s.params.contains("tint")) << s.id;
        const auto tint = s.params["tint"].get<std::vector<float>>();
        ASSERT_EQ(tint.size(), 3u);
        if (tint[0] == 0.0f) preset_with_min.insert(s.preset);
        components_apart |= tint[0] != tint[1];
        EXPECT_GE(s.width, 1u);
        EXPECT_TRUE(s.plugin_floor == -1 || s.plugin_floor == int32_t(s.floors) - 1) << s.id;
    }
    EXPECT_EQ(preset_with_min, (std::set<std::string>{"", "low", "high"}));
    EXPECT_TRUE(components_apart);
}

TEST(Combinations, AGlobalEffectIsNotCombinedWithLights) {
    PluginInfo plugin = plugin_with_everything();
    plugin.scope = "global";
    plugin.masks.clear();
    std::set<std::string> names;
    for (const CombinationFactor& f : combination_factors(plugin)) names.insert(f.name);
    EXPECT_FALSE(names.count("lights"));
    EXPECT_FALSE(names.count("masks"));
    EXPECT_FALSE(names.count("plugin floor"));
}

}  // namespace
}  // namespace acetate::harness
