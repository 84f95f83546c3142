// How a run is cut into shards (harness/shard_plan.hpp): `--shard K/N` read through the one
// number reader, the plan file every shard writes (the same bytes from each; another run's
// plan refused), and the merge's list of missing cases by the shard that owes them.

#include "shard_plan.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test_files.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;

TEST(ShardSelection, KOfNCountedFromZeroAndEveryOtherSpellingRefusedInOneLine) {
    auto first = parse_shard_selection("0/4", "--shard");
    ASSERT_TRUE(first) << first.error().message;
    EXPECT_EQ(first.value(), (ShardSelection{0, 4}));
    EXPECT_EQ(first->label(), "0/4");
    EXPECT_EQ(first->folder(), "0-of-4");
    EXPECT_TRUE(first->owns(0));
    EXPECT_TRUE(first->owns(8));
    EXPECT_FALSE(first->owns(3));
    auto last = parse_shard_selection("3/4", "--shard");
    ASSERT_TRUE(last);
    EXPECT_TRUE(last->owns(7));
    auto whole = parse_shard_selection("0/1", "--shard");
    ASSERT_TRUE(whole);
    EXPECT_TRUE(whole->owns(12345));

    const std::pair<const char*, const char*> refused[] = {
        {"4/4", "--shard: K: must be at most 3, got 4"},
        {"1/0", "--shard: N: must be at least 1, got 0"},
        {"-1/4", "--shard: K: "},
        {"1/4097", "--shard: N: must be at most 4096"},
        {"1", "--shard: must be K/N (shard K of N, K counted from 0), got \"1\""},
        {"1/4/2", "--shard: N: "},
        {"a/4", "--shard: K: "},
        {"", "--shard: must be K/N"},
    };
    for (const auto& [text, message] : refused) {
        auto r = parse_shard_selection(text, "--shard");
        ASSERT_FALSE(r) << text;
        EXPECT_TRUE(test::contains(r.error().message, message))
            << text << ": " << r.error().message;
        EXPECT_EQ(r.error().message.find('\n'), std::string::npos) << r.error().message;
    }
}

ShardPlan plan_of(unsigned shards, int strictness = 1) {
    ShardPlan p{"test.glow", "1.0.0", std::string(64, 'a'), strictness, 7, shards, {}};
    for (const char* id : {"contract/standard", "sizes/1x1", "sizes/odd", "loads/after-others"})
        p.cases.push_back({id, ValidationStage::AlphaTested});
    p.cases.push_back({"integration/harbour", ValidationStage::Integrated});
    return p;
}

TEST(ShardPlanFile, EveryShardWritesTheSamePlanAndAnotherRunsPlanIsRefused) {
    const fs::path dir = test::scratch_dir();
    ASSERT_TRUE(write_shard_plan(dir, plan_of(2)));
    const std::string bytes = test::read_file(dir / "plan.json");
    ASSERT_TRUE(write_shard_plan(dir, plan_of(2))) << "a second shard of the same run";
    EXPECT_EQ(test::read_file(dir / "plan.json"), bytes);

    auto read = read_shard_plan(dir);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->shards, 2u);
    ASSERT_EQ(read->cases.size(), 5u);
    EXPECT_EQ(read->cases[4].id, "integration/harbour");
    EXPECT_EQ(read->cases[4].stage, ValidationStage::Integrated);

    for (const ShardPlan& other : {plan_of(3), plan_of(2, 5)}) {
        auto refused = write_shard_plan(dir, other);
        ASSERT_FALSE(refused);
        EXPECT_TRUE(test::contains(refused.error().message,
                                   (dir / "plan.json").string() + ": the plan of another run ("))
            << refused.error().message;
        EXPECT_TRUE(test::contains(refused.error().message, "give each run its own folder"));
        EXPECT_EQ(test::read_file(dir / "plan.json"), bytes) << "the first run's plan stays";
    }

    test::write_text(dir / "plan.json", R"({"format": "acetate-shard-plan/1", "shards": 0})");
    auto bad = read_shard_plan(dir);
    ASSERT_FALSE(bad);
    EXPECT_TRUE(test::contains(bad.error().message, (dir / "plan.json").string() + ": "))
        << bad.error().message;
}

TEST(MissingByShard, OneLinePerShardNamingEveryMissingCase) {
    const std::vector<std::string> plan = {"a", "b", "c", "d", "e", "f", "g"};
    EXPECT_TRUE(missing_by_shard(plan, {plan.begin(), plan.end()}, 4).empty());
    // Shard 1/4 owns b and f; shard 2/4 owns c and g; d is shard 3/4's.
    const std::vector<std::string> lines = missing_by_shard(plan, {"a", "e", "d"}, 4);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0], "shard 1/4: 2 cases: b, f");
    EXPECT_EQ(lines[1], "shard 2/4: 2 cases: c, g");
    // Results of --case runs name no shard: one line.
    const std::vector<std::string> unsharded = missing_by_shard(plan, {"a", "b", "c"}, {});
    ASSERT_EQ(unsharded.size(), 1u);
    EXPECT_EQ(unsharded[0], "4 cases: d, e, f, g");
    EXPECT_EQ(missing_by_shard(plan, {"a", "b", "c", "d", "e", "f"}, 4).front(),
              "shard 2/4: 1 case: g");
}

}  // namespace
}  // namespace acetate::harness
