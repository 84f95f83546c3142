// Sign-offs are SSH signatures (registry/ssh_signature.hpp, docs/registry.md "Signatures"):
// a registry reader trusts a review or a promotion only when its signature verifies against
// the allowed signers, for the maintainer it names and the exact statement it signs. Forged,
// unlisted, altered and revoked sign-offs are dropped with one line naming the entry.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "registry.hpp"
#include "ssh_signature.hpp"
#include "test_files.hpp"
#include "test_signer.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

constexpr const char* kId = "org.example.glow";
constexpr const char* kVersion = "1.2.0";
const std::string kBinary(64, 'b');
const std::string kSource(64, 'c');

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// ALPHA_TESTED and INTEGRATED evidence for the binary: automated records carry no signature.
void record_evidence(Registry& r, const std::string& harness) {
    StageEvidence run;
    run.harness_version = harness;
    run.counts = {{"PASS", 3}};
    for (ValidationStage stage : {ValidationStage::AlphaTested, ValidationStage::Integrated})
        EXPECT_TRUE(r.record_evidence(kId, kVersion, kBinary, kSource, stage, run));
}

class Signatures : public ::testing::Test {
  protected:
    // A registry where the plugin is VALIDATED, its review by rita and its promotion by pat
    // signed with `review_key` and `promotion_key` (the test maintainer's by default).
    Registry validated(const fs::path& review_key = {}, const fs::path& promotion_key = {}) {
        Registry r;
        SignOff review{"rita@example.org", "2026-11-20T10:00:00Z", "read it all", kSource, ""};
        test::sign(review, kId, kVersion, ValidationStage::Reviewed, review_key);
        EXPECT_TRUE(r.record_review(kId, kVersion, kBinary, kSource, review));
        record_evidence(r, "signature-test");
        SignOff promotion{"pat@example.org", "2026-11-21T10:00:00Z", "evidence read", kSource, ""};
        test::sign(promotion, kId, kVersion, ValidationStage::Validated, promotion_key);
        EXPECT_TRUE(r.promote(kId, kVersion, promotion));
        return r;
    }

    // The registry as a reader sees it: written, read back, verified with `verifier`.
    static Registry as_read(const Registry& written, const SignatureVerifier& verifier) {
        auto read = Registry::parse(written.to_json(), "registry.json");
        EXPECT_TRUE(read) << read.error().message;
        Registry r = read ? std::move(read).value() : Registry();
        r.verify_sign_offs(verifier);
        return r;
    }

    SignatureVerifier verifier() const {
        return SignatureVerifier(test::test_signer().allowed_signers);
    }

    // `explain` for the plugin's binary after verification: the host's one line.
    static std::string why(const Registry& r) { return r.explain(kId, kBinary); }
};

TEST_F(Signatures, ASignedRegistryIsTrustedAfterARoundTrip) {
    const Registry written = validated();
    EXPECT_TRUE(contains(written.to_json(), "-----BEGIN SSH SIGNATURE-----"));
    const Registry r = as_read(written, verifier());
    EXPECT_TRUE(r.is_validated(kId, kBinary)) << why(r);
    EXPECT_TRUE(r.find(kId, kVersion)->distrusted.empty());
}

// Anyone who can write registry.json could write this entry: the records, the stage, the
// names, but no signature.
TEST_F(Signatures, AForgedEntryWithoutSignaturesIsNotTrusted) {
    Registry forged;
    ASSERT_TRUE(forged.record_review(kId, kVersion, kBinary, kSource, "rita@example.org", ""));
    record_evidence(forged, "forger");
    ASSERT_TRUE(forged.promote(kId, kVersion, "pat@example.org", ""));
    ASSERT_TRUE(forged.is_validated(kId, kBinary));  // unverified, it looks VALIDATED

    const Registry r = as_read(forged, verifier());
    EXPECT_FALSE(r.is_validated(kId, kBinary));
    EXPECT_EQ(r.binary_stage(kId, kBinary), ValidationStage::Unvalidated);
    EXPECT_EQ(why(r),
              "org.example.glow 1.2.0 is UNVALIDATED for this binary: the review by "
              "rita@example.org is not trusted: its signature is missing (the sign-off is not "
              "signed)");
}

TEST_F(Signatures, ASignatureFromAKeyNotAllowedIsNotTrusted) {
    const fs::path stranger = test::test_signer().unlisted_key;
    const Registry r = as_read(validated({}, stranger), verifier());
    EXPECT_EQ(r.binary_stage(kId, kBinary), ValidationStage::Integrated);
    EXPECT_TRUE(contains(why(r),
                         "org.example.glow 1.2.0 is INTEGRATED for this binary: the "
                         "promotion by pat@example.org is not trusted: its signature "
                         "was made by a key that allowed_signers does not list"))
        << why(r);
}

// A listed key signs for the names its line gives, no others.
TEST_F(Signatures, ASignatureInSomeoneElsesNameIsNotTrusted) {
    Registry r;
    SignOff review{"founders@acetate.dev", "2026-11-20T10:00:00Z", "", kSource, ""};
    test::sign(review, kId, kVersion, ValidationStage::Reviewed);
    ASSERT_TRUE(r.record_review(kId, kVersion, kBinary, kSource, review));
    r = as_read(r, verifier());
    EXPECT_EQ(r.binary_stage(kId, kBinary), ValidationStage::Unvalidated);
    EXPECT_TRUE(contains(why(r),
                         "its signature was made by rita@example.org, pat@example.org, "
                         "maintainers@example.org, policy-test@example.org's key, not "
                         "by founders@acetate.dev"))
        << why(r);
}

// A good signature copied onto other content: other notes, another source, another stage.
TEST_F(Signatures, ASignatureOverDifferentContentIsNotTrusted) {
    const Registry good = validated();
    const std::string text = good.to_json();
    const std::string notes_changed = [&] {
        std::string t = text;
        t.replace(t.find("evidence read"), 13, "evidence seen");
        return t;
    }();
    auto r = Registry::parse(notes_changed, "registry.json");
    ASSERT_TRUE(r) << r.error().message;
    r->verify_sign_offs(verifier());
    EXPECT_EQ(r->binary_stage(kId, kBinary), ValidationStage::Integrated);
    EXPECT_TRUE(contains(why(*r),
                         "the promotion by pat@example.org is not trusted: its "
                         "signature does not match what it claims to sign"))
        << why(*r);

    // The review's signature (for REVIEWED) presented as the promotion's (for VALIDATED).
    auto swapped = Registry::parse(text, "registry.json");
    ASSERT_TRUE(swapped);
    const RegistryEntry& e = *swapped->find(kId, kVersion);
    SignOff promotion = *e.promotion;
    SignOff review_as_promotion = *e.review;
    review_as_promotion.by = promotion.by;
    Registry reused = swapped.value();
    ASSERT_TRUE(reused.promote(kId, kVersion, review_as_promotion));
    reused = as_read(reused, verifier());
    EXPECT_EQ(reused.binary_stage(kId, kBinary), ValidationStage::Integrated) << why(reused);
}

TEST_F(Signatures, ARevokedKeyIsNotTrustedEvenWhereItIsAllowed) {
    // The allowed signers and a revoked_keys file beside them that lists the test key.
    const fs::path dir = test::scratch_dir();
    fs::copy_file(test::test_signer().allowed_signers, dir / "allowed_signers");
    test::write_text(dir / "revoked_keys",
                     "# revoked in a test\n" + test::read_file(test::test_signer().public_key));
    const SignatureVerifier revoking(dir / "allowed_signers");
    const Registry r = as_read(validated(), revoking);
    EXPECT_EQ(r.binary_stage(kId, kBinary), ValidationStage::Unvalidated);
    EXPECT_TRUE(contains(why(r),
                         "the review by rita@example.org is not trusted: its signature "
                         "was made by a revoked key (listed in " +
                             (dir / "revoked_keys").string() + ")"))
        << why(r);
    // Without the revocation the same registry holds.
    EXPECT_TRUE(as_read(validated(), verifier()).is_validated(kId, kBinary));
}

TEST_F(Signatures, NoAllowedSignersFileTrustsNothing) {
    const fs::path missing = test::scratch_dir() / "allowed_signers";
    const Registry r = as_read(validated(), SignatureVerifier(missing));
    EXPECT_EQ(r.binary_stage(kId, kBinary), ValidationStage::Unvalidated);
    EXPECT_TRUE(
        contains(why(r), "its signature cannot be checked: " + missing.string() + ": no such file"))
        << why(r);
}

TEST_F(Signatures, TheStatementNamesEverythingTheSignOffApproves) {
    const SignOff s{"rita@example.org", "2026-11-20T10:00:00Z", "line one\nline two", kSource,
                    "ignored"};
    EXPECT_EQ(sign_off_statement(kId, kVersion, ValidationStage::Reviewed, s),
              "{\"format\":\"acetate-signoff/1\",\"plugin\":\"org.example.glow\",\"version\":"
              "\"1.2.0\",\"stage\":\"REVIEWED\",\"source_digest\":\"" +
                  kSource +
                  "\",\"by\":\"rita@example.org\",\"at\":\"2026-11-20T10:00:00Z\",\"notes\":"
                  "\"line one\\nline two\"}\n");
}

// The committed sign-offs verify with the committed allowed signers: every fresh build
// trusts exactly these.
TEST_F(Signatures, TheCommittedSignOffsAreSignedByACommittedKey) {
    auto committed = Registry::load(fs::path(ACETATE_SOURCE_VALIDATION_DIR) / "signoffs.json");
    ASSERT_TRUE(committed) << committed.error().message;
    ASSERT_FALSE(committed->entries().empty());
    committed->verify_sign_offs(
        SignatureVerifier(fs::path(ACETATE_SOURCE_VALIDATION_DIR) / "allowed_signers"));
    for (const RegistryEntry& e : committed->entries()) {
        EXPECT_TRUE(e.distrusted.empty())
            << e.id << ": " << (e.distrusted.empty() ? "" : e.distrusted.begin()->second);
        EXPECT_TRUE(e.review) << e.id;
        EXPECT_TRUE(e.promotion) << e.id;
    }
}

}  // namespace
}  // namespace acetate
