// Sign-offs are SSH signatures (registry/ssh_signature.hpp, docs/registry.md "Signatures"):
// a registry reader trusts a review or a promotion only when its signature verifies against
// the allowed signers, for the maintainer it names and the exact statement it signs. Forged,
// unlisted, altered and revoked sign-offs are dropped with one line naming the entry.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "registry.hpp"
#include "ssh_signature.hpp"
#include "test_files.hpp"
#include "test_signer.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;

namespace fs = std::filesystem;

constexpr const char* kId = "org.example.glow";
constexpr const char* kVersion = "1.2.0";
const std::string kBinary(64, 'b');
const std::string kSource(64, 'c');

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

// Every trust file is a regular file of bounded size: revocations that cannot be read refuse
// every signature (ignoring them would switch revocation off), and neither a FIFO nor a device
// in a trust file's place makes a reader wait or read endless bytes.
TEST_F(Signatures, TrustFilesThatAreNotRegularFilesRefuseEverySignature) {
    struct Case {
        const char* what;
        std::function<void(const fs::path&)> make;
        const char* kind;
    };
    const std::vector<Case> cases = {
        {"FIFO", [](const fs::path& f) { ASSERT_EQ(::mkfifo(f.c_str(), 0600), 0); }, "a FIFO"},
        {"folder", [](const fs::path& f) { fs::create_directory(f); }, "a directory"},
        {"link to /dev/zero", [](const fs::path& f) { fs::create_symlink("/dev/zero", f); },
         "a character device"},
    };
    for (const char* file : {"revoked_keys", "allowed_signers"})
        for (const Case& c : cases) {
            SCOPED_TRACE(std::string(file) + " is a " + c.what);
            const fs::path dir = test::scratch_dir() / (std::string(file) + "-" + c.kind);
            fs::create_directories(dir);
            if (std::string(file) == "revoked_keys")
                fs::copy_file(test::test_signer().allowed_signers, dir / "allowed_signers");
            c.make(dir / file);
            if (HasFatalFailure()) return;
            const Registry r = as_read(validated(), SignatureVerifier(dir / "allowed_signers"));
            EXPECT_EQ(r.binary_stage(kId, kBinary), ValidationStage::Unvalidated);
            EXPECT_TRUE(
                contains(why(r), "its signature cannot be checked: " + (dir / file).string() +
                                     ": not a regular file (" + c.kind + ")"))
                << why(r);
        }
}

// A forged signature of megabytes is refused by its size, before ssh-keygen spends minutes
// reading it.
TEST_F(Signatures, AnOversizedSignatureIsRefusedBeforeItIsRead) {
    Registry r = validated();
    const RegistryEntry& e = r.entries().front();
    SignOff review = *e.review;
    review.signature = "-----BEGIN SSH SIGNATURE-----\n" + std::string(10 << 20, 'A') +
                       "\n-----END SSH SIGNATURE-----\n";
    auto checked = verifier().verify(
        review.by, sign_off_statement(kId, kVersion, ValidationStage::Reviewed, review),
        review.signature);
    ASSERT_FALSE(checked);
    EXPECT_EQ(checked.error().message,
              "is 10.0 MiB (10485819 bytes), over the 16 KiB limit for "
              "a signature");
}

// A signing key named by --key or ACETATE_SIGNING_KEY is read like every trust file: a FIFO or
// a device is refused in one line, not waited on.
TEST_F(Signatures, ASigningKeyThatIsNotARegularFileIsRefusedNotWaitedOn) {
    const fs::path fifo = test::scratch_dir() / "key-fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    auto from_fifo = ssh_sign(fifo, "statement\n");
    ASSERT_FALSE(from_fifo);
    EXPECT_EQ(from_fifo.error().message, fifo.string() + ": not a regular file (a FIFO)");
    auto from_device = ssh_sign("/dev/zero", "statement\n");
    ASSERT_FALSE(from_device);
    EXPECT_EQ(from_device.error().message, "/dev/zero: not a regular file (a character device)");
    // The same key as a regular file signs.
    EXPECT_TRUE(ssh_sign(test::test_signer().key, "statement\n"));
}

// A shard runner's key is listed for case results only (namespaces="acetate-case-result"): a
// review it signs is not trusted, though the same key's result signatures are.
TEST_F(Signatures, ARunnersKeyCannotSignASignOff) {
    const Registry r = as_read(validated(test::test_signer().runner_key), verifier());
    EXPECT_EQ(r.binary_stage(kId, kBinary), ValidationStage::Unvalidated);
    EXPECT_TRUE(contains(why(r), "the review by rita@example.org is not trusted: its signature "))
        << why(r);
    const std::string result = "{\"format\":\"acetate-case-result/2\"}\n";
    auto signature = ssh_sign(test::test_signer().runner_key, result, kCaseResultNamespace);
    ASSERT_TRUE(signature) << signature.error().message;
    EXPECT_TRUE(SignatureVerifier(test::test_signer().allowed_signers, kCaseResultNamespace)
                    .verify(test::kTestRunnerName, result, signature.value()));
}

// Third-party plugins (docs/registry.md): an outside author's key, trusted through
// `author_scopes` for their own plugin ids only. Their review of their plugin counts, marked as
// the author's; their review of anyone else's does not; their promotion of their own plugin does
// not either: VALIDATED needs an independent maintainer (here pat, the test maintainer).
TEST_F(Signatures, AnOutsideAuthorSignsForTheirOwnPluginsAndNeverPromotesThem) {
    const fs::path dir = test::scratch_dir();
    const std::string author_key =
        test::read_file(fs::path(test::test_signer().unlisted_key.string() + ".pub"));
    std::istringstream fields(author_key);
    std::string type, blob;
    fields >> type >> blob;
    test::write_text(dir / "allowed_signers",
                     test::read_file(test::test_signer().allowed_signers) +
                         "alice@glow.example namespaces=\"acetate-signoff\" " + type + " " + blob +
                         "\n");
    const SignatureVerifier with_author(dir / "allowed_signers");
    auto signed_by = [&](const std::string& by, ValidationStage stage, const fs::path& key) {
        SignOff s{by, "2026-11-20T10:00:00Z", "signed", kSource, ""};
        test::sign(s, kId, kVersion, stage, key);
        return s;
    };
    auto registry = [&](const SignOff& review, const SignOff& promotion) {
        Registry r;
        EXPECT_TRUE(r.record_review(kId, kVersion, kBinary, kSource, review));
        record_evidence(r, "signature-test");
        EXPECT_TRUE(r.promote(kId, kVersion, promotion));
        return as_read(r, with_author);
    };
    const SignOff alice_review = signed_by("alice@glow.example", ValidationStage::Reviewed,
                                           test::test_signer().unlisted_key);
    const SignOff alice_promotion = signed_by("alice@glow.example", ValidationStage::Validated,
                                              test::test_signer().unlisted_key);
    const SignOff pat_promotion =
        signed_by("pat@example.org", ValidationStage::Validated, test::test_signer().key);

    // Without a scope alice is a maintainer like any other (the control).
    EXPECT_TRUE(registry(alice_review, alice_promotion).is_validated(kId, kBinary));

    // Scoped to another vendor's ids: nothing she signs for org.example.glow counts.
    test::write_text(dir / "author_scopes", "# outside authors\nalice@glow.example com.glow.*\n");
    Registry elsewhere = registry(alice_review, pat_promotion);
    EXPECT_EQ(elsewhere.binary_stage(kId, kBinary), ValidationStage::Unvalidated);
    EXPECT_TRUE(contains(why(elsewhere),
                         "the review by alice@glow.example is not trusted: alice@glow.example is "
                         "an outside author who may sign for com.glow.* only"))
        << why(elsewhere);

    // Scoped to her own ids: her review counts and is marked hers; her promotion does not.
    test::write_text(dir / "author_scopes", "alice@glow.example com.glow.*,org.example.*\n");
    Registry own = registry(alice_review, alice_promotion);
    EXPECT_EQ(own.binary_stage(kId, kBinary), ValidationStage::Integrated);
    EXPECT_TRUE(own.entries().front().review_by_author);
    EXPECT_TRUE(contains(why(own),
                         "the promotion by alice@glow.example is not trusted: alice@glow.example "
                         "is the plugin's own author; VALIDATED needs a promotion by an "
                         "independent maintainer"))
        << why(own);
    // An independent maintainer's promotion over her review: VALIDATED.
    Registry independent = registry(alice_review, pat_promotion);
    EXPECT_TRUE(independent.is_validated(kId, kBinary)) << why(independent);
    EXPECT_TRUE(independent.entries().front().review_by_author);

    // Scopes that cannot be read trust nothing, as revocations that cannot be read do.
    fs::remove(dir / "author_scopes");
    fs::create_directory(dir / "author_scopes");
    EXPECT_EQ(registry(alice_review, pat_promotion).binary_stage(kId, kBinary),
              ValidationStage::Unvalidated);
}

}  // namespace
}  // namespace acetate
