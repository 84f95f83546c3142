// Waivers and strictness in the registry (registry/registry.hpp, docs/registry.md "Waivers"):
// a waiver is granted on reviewed code for one check until a day, is bound to the source,
// round-trips through the file, blocks promotion once expired; evidence below the default
// strictness is promoted only under a waiver of "strictness". No GPU needed.

#include <gtest/gtest.h>

#include <string>

#include "core/sha256.hpp"
#include "registry.hpp"

namespace acetate {
namespace {

using Stage = ValidationStage;

const std::string kId = "org.acetate.glow";
const std::string kVersion = "2.0.0";
const std::string kBinary = sha256_hex("binary");
const std::string kRebuilt = sha256_hex("binary, rebuilt");
const std::string kSource = sha256_hex("source");
const std::string kEdited = sha256_hex("source, edited");
const std::string kNow = "2026-11-26T12:00:00Z";

Registry reviewed() {
    Registry r;
    r.set_clock([] { return kNow; });
    EXPECT_TRUE(r.record_review(kId, kVersion, kBinary, kSource, "alice@example.org", "read"));
    return r;
}

Waiver waiver(std::string check, std::string until = "2026-12-31") {
    return Waiver{
        std::move(check), "a fringe by design", "bob@example.org", "", std::move(until), ""};
}

// Reviewed, then both automated stages at `strictness`.
Registry integrated(int strictness) {
    Registry r = reviewed();
    StageEvidence run;
    run.harness_version = "0.1.0";
    run.counts = {{"PASS", 10}};
    run.strictness = strictness;
    EXPECT_TRUE(r.record_evidence(kId, kVersion, kBinary, kSource, Stage::AlphaTested, run));
    EXPECT_TRUE(r.record_evidence(kId, kVersion, kBinary, kSource, Stage::Integrated, run));
    return r;
}

std::string refusal(const Result<void>& r) {
    return r ? "(accepted)" : r.error().message;
}

std::string parse_error(const std::string& text) {
    auto parsed = Registry::parse(text, "r.json");
    return parsed ? "(parsed)" : parsed.error().message;
}

TEST(RegistryWaivers, AWaiverNeedsAReviewAReasonAndADayToCome) {
    Registry fresh;
    fresh.set_clock([] { return kNow; });
    EXPECT_EQ(refusal(fresh.waive(kId, kVersion, kBinary, kSource, waiver("reach"))),
              "org.acetate.glow 2.0.0: waiver refused: it is UNVALIDATED for this source (the "
              "registry has no record of it); a waiver is granted on reviewed code");
    Registry r = reviewed();
    Waiver no_reason = waiver("reach");
    no_reason.reason = "  ";
    EXPECT_EQ(refusal(r.waive(kId, kVersion, kBinary, kSource, no_reason)),
              "org.acetate.glow 2.0.0: waiver refused: the reason is empty (a waiver says why)");
    EXPECT_EQ(refusal(r.waive(kId, kVersion, kBinary, kSource, waiver("reach", "2026-11-25"))),
              "org.acetate.glow 2.0.0: waiver refused: --until 2026-11-25 is already past");
    EXPECT_EQ(refusal(r.waive(kId, kVersion, kBinary, kSource, waiver("reach", "26-12-31"))),
              "org.acetate.glow 2.0.0: waiver refused: --until \"26-12-31\" is not a day "
              "(YYYY-MM-DD)");
    EXPECT_TRUE(r.find(kId, kVersion)->waivers.empty());

    // Today is still within the waiver; a second waiver of one check replaces the first.
    ASSERT_TRUE(r.waive(kId, kVersion, kBinary, kSource, waiver("reach", "2026-11-26")));
    ASSERT_TRUE(r.waive(kId, kVersion, kBinary, kSource, waiver("reach", "2027-01-31")));
    ASSERT_TRUE(r.waive(kId, kVersion, kBinary, kSource, waiver("memory")));
    const auto& waivers = r.find(kId, kVersion)->waivers;
    ASSERT_EQ(waivers.size(), 2u);
    EXPECT_EQ(waivers[0].check, "memory");  // sorted by check
    EXPECT_EQ(waivers[1].until, "2027-01-31");
    EXPECT_EQ(waivers[1].at, kNow);
    EXPECT_EQ(waivers[1].source_digest, kSource);
}

TEST(RegistryWaivers, WaiversRoundTripAndBindToTheSource) {
    Registry r = reviewed();
    ASSERT_TRUE(r.waive(kId, kVersion, kBinary, kSource, waiver("reach")));
    auto read = Registry::parse(r.to_json(), "registry.json");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->find(kId, kVersion)->waivers, r.find(kId, kVersion)->waivers);

    // A rebuild keeps it (it is bound to the source); a source change drops it.
    ASSERT_TRUE(r.record_review(kId, kVersion, kRebuilt, kSource, "alice@example.org", ""));
    EXPECT_EQ(r.find(kId, kVersion)->waivers.size(), 1u);
    ASSERT_TRUE(r.record_review(kId, kVersion, kRebuilt, kEdited, "alice@example.org", ""));
    EXPECT_TRUE(r.find(kId, kVersion)->waivers.empty());

    // A hand-edited waiver: for another source, or with a malformed day.
    Registry other = reviewed();
    ASSERT_TRUE(other.waive(kId, kVersion, kBinary, kSource, waiver("reach")));
    std::string text = other.to_json();
    const size_t until = text.find("2026-12-31");
    std::string bad_day = text;
    bad_day.replace(until, 10, "2026-13-01");
    EXPECT_EQ(parse_error(bad_day),
              "r.json: plugins[0].waivers[0].until: \"2026-13-01\" is not a day (YYYY-MM-DD)");
    std::string moved = text;
    const size_t digest = moved.rfind(kSource);
    moved.replace(digest, kSource.size(), kEdited);
    EXPECT_NE(parse_error(moved).find("r.json: plugins[0].waivers[0].source_digest: "),
              std::string::npos)
        << parse_error(moved);
}

TEST(RegistryWaivers, PromotionBelowTheDefaultStrictnessNeedsAWaiver) {
    Registry r = integrated(1);
    EXPECT_EQ(refusal(r.promote(kId, kVersion, "bob@example.org", "")),
              "org.acetate.glow 2.0.0: promotion refused: its evidence was taken at strictness "
              "1, below the default 5; validate again at 5 or more, or waive \"strictness\" "
              "saying why");
    ASSERT_TRUE(r.waive(kId, kVersion, kBinary, kSource, waiver(kStrictnessWaiver)));
    EXPECT_TRUE(r.promote(kId, kVersion, "bob@example.org", ""));
    EXPECT_TRUE(r.is_validated(kId, kBinary));

    // At the default, or from a harness that did not record it (0), no waiver is needed.
    for (int strictness : {kDefaultStrictness, 10, 0}) {
        Registry s = integrated(strictness);
        EXPECT_TRUE(s.promote(kId, kVersion, "bob@example.org", "")) << strictness;
    }
}

TEST(RegistryWaivers, AnExpiredWaiverBlocksPromotion) {
    Registry r = integrated(kDefaultStrictness);
    ASSERT_TRUE(r.waive(kId, kVersion, kBinary, kSource, waiver("reach", "2026-11-30")));
    r.set_clock([] { return std::string("2026-12-01T00:00:00Z"); });
    EXPECT_EQ(refusal(r.promote(kId, kVersion, "bob@example.org", "")),
              "org.acetate.glow 2.0.0: promotion refused: the waiver of \"reach\" expired on "
              "2026-11-30 (by bob@example.org: a fringe by design); renew it or fix the plugin");
    EXPECT_EQ(r.binary_stage(kId, kBinary), Stage::Integrated);
}

}  // namespace
}  // namespace acetate
