// The validation registry (registry/registry.hpp): stages advance in order and are never
// skipped; a rebuilt binary loses its automated stages and a source change its sign-offs; the
// host's check pins the binary; the file round-trips, names the field when malformed, and
// survives concurrent writers and a writer killed mid-write. Hostile files (FIFOs, devices,
// oversized, duplicate keys) are in registry_hostile_files_test.cpp. No GPU needed.

#include "registry.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "core/input_file.hpp"
#include "registry_fixtures.hpp"

namespace acetate {
namespace {

using namespace registry_test;
using ::acetate::test::read_file;
using ::acetate::test::scratch_dir;

TEST(Registry, StagesAdvanceInOrder) {
    Registry r = fixed_clock_registry();
    EXPECT_EQ(stage_of(r, kBinaryA, kSource1), Stage::Unvalidated);

    ASSERT_TRUE(r.record_review(kId, kVersion, kBinaryA, kSource1, "alice", "read it all"));
    EXPECT_EQ(stage_of(r, kBinaryA, kSource1), Stage::Reviewed);
    const RegistryEntry* e = r.find(kId, kVersion);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->review, (SignOff{"alice", kNow, "read it all", kSource1, ""}));

    ASSERT_TRUE(
        r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::AlphaTested, passing_run()));
    EXPECT_EQ(stage_of(r, kBinaryA, kSource1), Stage::AlphaTested);
    ASSERT_TRUE(
        r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::Integrated, passing_run()));
    EXPECT_EQ(stage_of(r, kBinaryA, kSource1), Stage::Integrated);
    ASSERT_TRUE(r.promote(kId, kVersion, "bob", "ok"));
    EXPECT_EQ(stage_of(r, kBinaryA, kSource1), Stage::Validated);

    e = r.find(kId, kVersion);
    EXPECT_EQ(e->stage(), Stage::Validated);
    EXPECT_EQ(e->alpha_tested->binary_sha256, kBinaryA);
    EXPECT_EQ(e->alpha_tested->at, kNow);
    EXPECT_EQ(e->promotion, (SignOff{"bob", kNow, "ok", kSource1, ""}));
}

TEST(Registry, StageNamesParse) {
    EXPECT_EQ(parse_validation_stage("alpha-tested"), Stage::AlphaTested);
    EXPECT_EQ(parse_validation_stage("INTEGRATED"), Stage::Integrated);
    EXPECT_EQ(parse_validation_stage("nearly"), std::nullopt);
    EXPECT_STREQ(to_string(Stage::AlphaTested), "ALPHA_TESTED");
}

TEST(Registry, ReviewNeedsReviewerAndWellFormedIdentity) {
    Registry r;
    auto empty = r.record_review(kId, kVersion, kBinaryA, kSource1, " ", "notes");
    ASSERT_FALSE(empty);
    EXPECT_EQ(empty.error().message,
              "org.acetate.bloom 1.2.0: review refused: the reviewer's name is empty (a sign-off "
              "says who signed)");
    EXPECT_FALSE(r.record_review(kId, kVersion, "not-a-hash", kSource1, "alice", ""));
    EXPECT_FALSE(r.record_review(kId, "1.2", kBinaryA, kSource1, "alice", ""));
    EXPECT_FALSE(r.record_review("Bloom", kVersion, kBinaryA, kSource1, "alice", ""));
    auto no_digest = r.record_review(kId, kVersion, kBinaryA, "", "alice", "");
    ASSERT_FALSE(no_digest);
    EXPECT_NE(no_digest.error().message.find("no source digest"), std::string::npos);
    EXPECT_TRUE(r.entries().empty()) << "a refused operation records nothing";
}

TEST(Registry, SkippingIsRefused) {
    Registry r;
    auto alpha_first =
        r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::AlphaTested, passing_run());
    ASSERT_FALSE(alpha_first);
    EXPECT_EQ(alpha_first.error().message,
              "org.acetate.bloom 1.2.0: ALPHA_TESTED evidence refused: it is UNVALIDATED and "
              "stages are never skipped; REVIEWED comes first (the registry has no record of "
              "it)");

    ASSERT_TRUE(r.record_review(kId, kVersion, kBinaryA, kSource1, "alice", ""));
    auto integrated_early =
        r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::Integrated, passing_run());
    ASSERT_FALSE(integrated_early);
    EXPECT_EQ(integrated_early.error().message,
              "org.acetate.bloom 1.2.0: INTEGRATED evidence refused: it is REVIEWED and stages "
              "are never skipped; ALPHA_TESTED comes first (no ALPHA_TESTED evidence for binary " +
                  kBinaryA.substr(0, 12) + ")");
    EXPECT_EQ(stage_of(r, kBinaryA, kSource1), Stage::Reviewed);
    EXPECT_FALSE(
        r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::Validated, passing_run()))
        << "VALIDATED takes a promotion, not evidence";
}

TEST(Registry, FailingRunIsNotEvidence) {
    Registry r;
    ASSERT_TRUE(r.record_review(kId, kVersion, kBinaryA, kSource1, "alice", ""));
    StageEvidence failed = passing_run();
    failed.counts["CRASH"] = 1;
    auto refused = r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::AlphaTested, failed);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("the run has 1 CRASH"), std::string::npos);
    EXPECT_EQ(stage_of(r, kBinaryA, kSource1), Stage::Reviewed);
}

TEST(Registry, RebuiltBinaryLosesAutomatedStagesKeepsReview) {
    Registry r = validated_registry();
    EXPECT_EQ(stage_of(r, kBinaryB, kSource1), Stage::Reviewed);
    EXPECT_EQ(stage_of(r, kBinaryA, kSource1), Stage::Validated) << "a query changes nothing";

    // Re-running the automated stages on the rebuilt binary: the promotion (bound to the
    // unchanged source) holds again once they pass, with nobody signing anything.
    ASSERT_TRUE(
        r.record_evidence(kId, kVersion, kBinaryB, kSource1, Stage::AlphaTested, passing_run()));
    const RegistryEntry* e = r.find(kId, kVersion);
    EXPECT_EQ(e->binary_sha256, kBinaryB);
    EXPECT_FALSE(e->integrated) << "binary A's integration evidence no longer holds";
    EXPECT_EQ(stage_of(r, kBinaryB, kSource1), Stage::AlphaTested);
    EXPECT_EQ(stage_of(r, kBinaryA, kSource1), Stage::Reviewed);
    ASSERT_TRUE(
        r.record_evidence(kId, kVersion, kBinaryB, kSource1, Stage::Integrated, passing_run()));
    EXPECT_EQ(stage_of(r, kBinaryB, kSource1), Stage::Validated);
}

TEST(Registry, SourceChangeLosesSignOffs) {
    Registry r = validated_registry();
    EXPECT_EQ(stage_of(r, kBinaryB, kSource2), Stage::Unvalidated);
    auto evidence =
        r.record_evidence(kId, kVersion, kBinaryB, kSource2, Stage::AlphaTested, passing_run());
    ASSERT_FALSE(evidence);
    EXPECT_NE(evidence.error().message.find("REVIEWED comes first (no review sign-off for source " +
                                            kSource2.substr(0, 12) + " (signed for " +
                                            kSource1.substr(0, 12) + "))"),
              std::string::npos)
        << evidence.error().message;

    ASSERT_TRUE(r.record_review(kId, kVersion, kBinaryB, kSource2, "carol", "new blur"));
    const RegistryEntry* e = r.find(kId, kVersion);
    EXPECT_EQ(e->stage(), Stage::Reviewed);
    EXPECT_FALSE(e->promotion) << "the promotion vouched for the old source";
    EXPECT_FALSE(e->alpha_tested);
    EXPECT_EQ(e->review->by, "carol");
}

TEST(Registry, PromoteOnlyFromIntegrated) {
    Registry r;
    EXPECT_FALSE(r.promote(kId, kVersion, "bob", "")) << "unknown plugin";
    ASSERT_TRUE(r.record_review(kId, kVersion, kBinaryA, kSource1, "alice", ""));
    auto from_reviewed = r.promote(kId, kVersion, "bob", "");
    ASSERT_FALSE(from_reviewed);
    EXPECT_NE(from_reviewed.error().message.find(
                  "org.acetate.bloom 1.2.0: promotion refused: only an INTEGRATED plugin is "
                  "promoted; it is REVIEWED"),
              std::string::npos);
    ASSERT_TRUE(
        r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::AlphaTested, passing_run()));
    EXPECT_FALSE(r.promote(kId, kVersion, "bob", ""));
    ASSERT_TRUE(
        r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::Integrated, passing_run()));
    EXPECT_FALSE(r.promote(kId, kVersion, "", "")) << "a promotion names who";
    ASSERT_TRUE(r.promote(kId, kVersion, "bob", ""));
    auto again = r.promote(kId, kVersion, "bob", "");
    ASSERT_FALSE(again);
    EXPECT_NE(again.error().message.find("already VALIDATED"), std::string::npos);
}

TEST(Registry, IsValidatedPinsTheBinary) {
    const Registry r = validated_registry();
    EXPECT_TRUE(r.is_validated(kId, kBinaryA));
    EXPECT_FALSE(r.is_validated(kId, kBinaryB));
    EXPECT_FALSE(r.is_validated("org.acetate.other", kBinaryA));
    EXPECT_TRUE(r.require_validated(kId, kVersion, kBinaryA, kSource1));
    auto changed = r.require_validated(kId, kVersion, kBinaryB, kSource1);
    ASSERT_FALSE(changed);
    EXPECT_EQ(changed.error().message,
              "org.acetate.bloom 1.2.0: is REVIEWED, not VALIDATED: no ALPHA_TESTED evidence "
              "for binary " +
                  kBinaryB.substr(0, 12) + " (recorded for " + kBinaryA.substr(0, 12) + ")");
    auto unknown = r.require_validated("org.acetate.other", "1.0.0", kBinaryA, kSource1);
    ASSERT_FALSE(unknown);
    EXPECT_EQ(unknown.error().message,
              "org.acetate.other 1.0.0: is UNVALIDATED, not VALIDATED: the registry has no "
              "record of it");
}

// What `acetate render` asks before loading a file: it knows the binary's SHA-256, not yet the
// plugin's version or source digest.
TEST(Registry, BinaryStageAndExplainJudgeTheBinaryAlone) {
    const std::string a = kBinaryA.substr(0, 12), b = kBinaryB.substr(0, 12);
    Registry r = validated_registry();
    EXPECT_EQ(r.binary_stage(kId, kBinaryA), Stage::Validated);
    EXPECT_EQ(r.explain(kId, kBinaryA), "org.acetate.bloom 1.2.0 is VALIDATED for this binary");
    // An empty id matches any plugin recorded with that binary (a file loaded by path).
    EXPECT_EQ(r.binary_stage("", kBinaryA), Stage::Validated);
    EXPECT_EQ(r.explain("", kBinaryA), "org.acetate.bloom 1.2.0 is VALIDATED for this binary");

    // A binary the registry never saw: UNVALIDATED for it, and what the registry has instead.
    EXPECT_EQ(r.binary_stage(kId, kBinaryB), Stage::Unvalidated);
    EXPECT_EQ(r.explain(kId, kBinaryB),
              "org.acetate.bloom is UNVALIDATED for this binary: recorded only for other "
              "binaries: 1.2.0 VALIDATED for " +
                  a);
    EXPECT_EQ(r.binary_stage("", kBinaryB), Stage::Unvalidated);
    EXPECT_EQ(r.explain("", kBinaryB), "this binary is UNVALIDATED: no record of it");
    // A plugin the registry never saw; the same binary under another id does not count.
    EXPECT_EQ(r.binary_stage("org.acetate.other", kBinaryA), Stage::Unvalidated);
    EXPECT_EQ(r.explain("org.acetate.other", kBinaryA),
              "org.acetate.other is UNVALIDATED: no record of it");
    EXPECT_EQ(Registry().explain(kId, kBinaryA),
              "org.acetate.bloom is UNVALIDATED: no record of it");

    // Recorded with this binary but short of VALIDATED: its stage and the first missing record.
    ASSERT_TRUE(r.record_review(kId, kVersion, kBinaryB, kSource1, "alice", "rebuilt"));
    EXPECT_EQ(r.binary_stage(kId, kBinaryB), Stage::Reviewed);
    EXPECT_EQ(r.explain(kId, kBinaryB),
              "org.acetate.bloom 1.2.0 is REVIEWED for this binary: no ALPHA_TESTED evidence for "
              "binary " +
                  b);
    EXPECT_EQ(r.binary_stage(kId, kBinaryA), Stage::Unvalidated);
    ASSERT_TRUE(
        r.record_evidence(kId, kVersion, kBinaryB, kSource1, Stage::AlphaTested, passing_run()));
    EXPECT_EQ(r.explain(kId, kBinaryB),
              "org.acetate.bloom 1.2.0 is ALPHA_TESTED for this binary: no INTEGRATED evidence "
              "for binary " +
                  b);
    // Several versions: the highest stage held for this binary counts, and all are listed.
    ASSERT_TRUE(r.record_review(kId, "1.3.0", kBinaryA, kSource2, "carol", ""));
    EXPECT_EQ(r.binary_stage(kId, kBinaryA), Stage::Reviewed);
    EXPECT_EQ(r.explain(kId, sha256_hex("binary C")),
              "org.acetate.bloom is UNVALIDATED for this binary: recorded only for other "
              "binaries: 1.2.0 ALPHA_TESTED for " +
                  b + ", 1.3.0 REVIEWED for " + a);

    // The policy agrees with is_validated for every id and binary asked above.
    for (const std::string& id : {kId, std::string("org.acetate.other")})
        for (const std::string& binary : {kBinaryA, kBinaryB})
            EXPECT_EQ(r.binary_stage(id, binary) == Stage::Validated, r.is_validated(id, binary))
                << id << " " << binary;
}

TEST_F(RegistryFiles, JsonRoundTripAndMarkdown) {
    Registry r = validated_registry();
    ASSERT_TRUE(r.record_review("org.acetate.lighting", "1.10.0", kBinaryB, kSource2, "dave",
                                "multi\nline | notes"));
    ASSERT_TRUE(r.record_review("org.acetate.lighting", "1.9.0", kBinaryA, kSource2, "dave", ""));
    const std::string text = r.to_json();

    auto parsed = Registry::parse(text, "registry.json");
    ASSERT_TRUE(parsed) << parsed.error().message;
    EXPECT_EQ(parsed->entries(), r.entries());
    EXPECT_EQ(parsed->to_json(), text) << "the same registry gives the same bytes";
    ASSERT_EQ(r.entries().size(), 3u);
    EXPECT_EQ(r.entries()[1].version, "1.9.0") << "versions sort numerically";

    const fs::path& dir = dir_;
    ASSERT_TRUE(r.save(dir / "registry.json"));
    auto loaded = Registry::load(dir / "registry.json");
    ASSERT_TRUE(loaded) << loaded.error().message;
    EXPECT_EQ(loaded->entries(), r.entries());

    const std::string md = render_registry_markdown(r, "registry.json");
    EXPECT_NE(md.find("| `org.acetate.bloom` | 1.2.0 | **VALIDATED** | `" + kBinaryA.substr(0, 12) +
                      "` | `" + kSource1.substr(0, 12) + "` | alice, " + kNow),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("bob, " + kNow), std::string::npos);
    EXPECT_NE(md.find("41 PASS"), std::string::npos);
    EXPECT_NE(md.find("report `reports/bloom/index.html`"), std::string::npos);
    EXPECT_NE(md.find("multi line \\| notes"), std::string::npos) << "notes stay on one line";
}

TEST_F(RegistryFiles, MissingFileIsAnEmptyRegistry) {
    auto loaded = Registry::load(dir_ / "none.json");
    ASSERT_TRUE(loaded);
    EXPECT_TRUE(loaded->entries().empty());
}

TEST_F(RegistryFiles, MalformedFileNamesTheField) {
    const std::string good = validated_registry().to_json();
    auto edited = [&](const std::string& from, const std::string& to) {
        std::string s = good;
        const size_t at = s.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return at == std::string::npos ? s : s.replace(at, from.size(), to);
    };
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"{ not json", "reg.json: malformed JSON: "},
        {good.substr(0, good.size() / 2), "reg.json: malformed JSON: parse error at line "},
        {edited("acetate-registry/1", "acetate-registry/2"),
         "reg.json: format: \"acetate-registry/2\" is not \"acetate-registry/1\""},
        {edited("\"at\": \"" + kNow, "\"at\": \"yesterday"),
         "reg.json: plugins[0].review.at: \"yesterday\" is not ISO-8601 UTC"},
        {edited("\"binary_sha256\"", "\"binary_sha\""),
         "reg.json: plugins[0]: unknown field \"binary_sha\""},
        {edited("\"stage\": \"VALIDATED\"", "\"stage\": \"INTEGRATED\""),
         "reg.json: plugins[0].stage: says INTEGRATED but its records support VALIDATED"},
        {edited("\"PASS\": 41", "\"FAIL\": 41"),
         "reg.json: plugins[0].alpha_tested.counts.FAIL: evidence records passing runs only"},
        {edited("\"by\": \"alice\"", "\"by\": \"\""),
         "reg.json: plugins[0].review.by: must not "
         "be empty"},
        {edited("\"version\": \"1.2.0\"", "\"version\": 1"),
         "reg.json: plugins[0].version: must be a string, got 1"},
        {edited("\"plugins\": [", "\"plugins\": [{},"),
         "reg.json: plugins[0]: missing required field \"id\""},
    };
    for (const auto& [text, expected] : cases) {
        auto parsed = Registry::parse(text, "reg.json");
        ASSERT_FALSE(parsed) << "accepted: " << expected;
        EXPECT_EQ(parsed.error().code, ErrorCode::InvalidInput);
        EXPECT_EQ(parsed.error().message.find('\n'), std::string::npos) << "one line";
        EXPECT_LT(parsed.error().message.size(), 300u) << parsed.error().message;
        EXPECT_EQ(parsed.error().message.rfind(expected, 0), 0u)
            << "got:      " << parsed.error().message << "\nexpected: " << expected;
    }
    // The same entry twice.
    const fs::path& dir = dir_;
    std::string doubled = good;
    const size_t open = doubled.find("[\n") + 2, close = doubled.rfind("\n  ]");
    const std::string entry = doubled.substr(open, close - open);
    doubled.insert(close, ",\n" + entry);
    std::ofstream(dir / "twice.json") << doubled;
    auto twice = Registry::load(dir / "twice.json");
    ASSERT_FALSE(twice);
    EXPECT_EQ(twice.error().message, (dir / "twice.json").string() +
                                         ": plugins[1]: org.acetate.bloom 1.2.0 appears twice");
}

TEST_F(RegistryFiles, ConcurrentUpdatesLoseNothing) {
    const fs::path& dir = dir_;
    const fs::path file = dir / "registry.json", markdown = dir / "VALIDATION-REGISTRY.md";
    constexpr int kChildren = 4, kUpdates = 20;
    std::vector<pid_t> children;
    for (int c = 0; c < kChildren; ++c) {
        children.push_back(fork_child([&] {
            for (int i = 0; i < kUpdates; ++i) {
                auto updated = Registry::update(
                    file,
                    [&](Registry& r) -> Result<void> {
                        // Widens the read-modify-write window: without the lock, another
                        // child's write would land in it and be lost.
                        std::this_thread::sleep_for(std::chrono::milliseconds(2));
                        return r.record_review("org.test.child" + std::to_string(c),
                                               "1.0." + std::to_string(i), kBinaryA, kSource1,
                                               "child", "");
                    },
                    markdown);
                if (!updated) return 1;
            }
            return 0;
        }));
    }
    for (pid_t pid : children) {
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
    auto loaded = Registry::load(file);
    ASSERT_TRUE(loaded) << loaded.error().message;
    EXPECT_EQ(loaded->entries().size(), size_t(kChildren * kUpdates));
    for (int c = 0; c < kChildren; ++c)
        for (int i = 0; i < kUpdates; ++i)
            EXPECT_NE(
                loaded->find("org.test.child" + std::to_string(c), "1.0." + std::to_string(i)),
                nullptr);
    EXPECT_EQ(read_file(markdown), render_registry_markdown(*loaded, "registry.json"));
}

std::vector<fs::path> temporaries_in(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const auto& item : fs::directory_iterator(dir))
        if (item.path().filename().string().find(".tmp-") != std::string::npos)
            out.push_back(item.path());
    return out;
}

TEST_F(RegistryFiles, WriterKilledMidWriteLeavesPreviousFile) {
    const fs::path& dir = dir_;
    const fs::path file = dir / "registry.json";
    ASSERT_TRUE(Registry::update(file, [](Registry& r) {
        return r.record_review(kId, kVersion, kBinaryA, kSource1, "alice", "");
    }));
    const std::string before = read_file(file);

    // The child records a review with 32 MiB of notes, so serialising and writing take long
    // enough to be caught: the parent kills it a few milliseconds after it takes the lock.
    const int lock =
        ::open((dir / "registry.json.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    ASSERT_GE(lock, 0);
    const pid_t pid = fork_child([&] {
        auto updated = Registry::update(file, [](Registry& r) {
            return r.record_review("org.acetate.huge", "1.0.0", kBinaryB, kSource2, "mallory",
                                   std::string(32 << 20, 'x'));
        });
        return updated ? 0 : 1;
    });
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    bool caught_writing = false;
    while (!caught_writing && std::chrono::steady_clock::now() < deadline) {
        if (::flock(lock, LOCK_EX | LOCK_NB) == 0)
            ::flock(lock, LOCK_UN);  // not yet: the child has not taken the lock
        else
            caught_writing = errno == EWOULDBLOCK;
        if (!caught_writing) std::this_thread::yield();
    }
    ::usleep(5000);
    ::kill(pid, SIGKILL);
    ::close(lock);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(caught_writing) << "the child never took the lock";
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child finished before it was killed";

    EXPECT_EQ(read_file(file), before) << "the previous registry is intact";
    // The write goes through an unnamed temporary: a killed writer leaves nothing behind.
    EXPECT_TRUE(temporaries_in(dir).empty()) << "the killed writer left a temporary";
    // The kill released the lock; the next update works.
    ASSERT_TRUE(Registry::update(file, [](Registry& r) {
        return r.record_review("org.acetate.next", "1.0.0", kBinaryB, kSource2, "alice", "");
    }));
    EXPECT_TRUE(temporaries_in(dir).empty());
    auto loaded = Registry::load(file);
    ASSERT_TRUE(loaded) << loaded.error().message;
    EXPECT_EQ(loaded->entries().size(), 2u);
}

TEST_F(RegistryFiles, WritersKilledAtRandomPointsNeverCorruptTheFile) {
    const fs::path& dir = dir_;
    const fs::path file = dir / "registry.json";
    std::mt19937 random(2025);  // fixed seed: the same kill times every run
    size_t entries_before = 0;
    for (int round = 0; round < 8; ++round) {
        const pid_t pid = fork_child([&] {
            for (int i = 0;; ++i) {
                auto updated = Registry::update(file, [&](Registry& r) {
                    return r.record_review("org.test.round" + std::to_string(round),
                                           "1.0." + std::to_string(i), kBinaryA, kSource1, "writer",
                                           std::string(256 << 10, 'n'));
                });
                if (!updated) return 1;
            }
        });
        std::this_thread::sleep_for(std::chrono::milliseconds(random() % 60));
        ::kill(pid, SIGKILL);
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        ASSERT_TRUE(WIFSIGNALED(status)) << "round " << round << ": the writer failed";

        auto loaded = Registry::load(file);
        ASSERT_TRUE(loaded) << "round " << round << ": " << loaded.error().message;
        EXPECT_GE(loaded->entries().size(), entries_before) << "round " << round;
        entries_before = loaded->entries().size();
    }
}

}  // namespace
}  // namespace acetate
