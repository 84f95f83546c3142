// The in-process signature check (registry/sshsig_in_process.hpp) beside ssh-keygen's: for each
// kind of signature a registry can hold, both paths of SignatureVerifier agree, and the
// in-process one decides the common case itself (so a registry of thousands of sign-offs reads
// without a process per signature) while leaving every file it does not fully understand to
// ssh-keygen.

#include "sshsig_in_process.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "ssh_signature.hpp"
#include "test_files.hpp"
#include "test_signer.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

struct Signed {
    std::string message, signature;
};

Signed sign_as(const fs::path& key, const std::string& message, const char* name_space) {
    auto signature = ssh_sign(key, message, name_space);
    EXPECT_TRUE(signature) << signature.error().message;
    return {message, signature ? signature.value() : std::string()};
}

class InProcessSignatures : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        fs::copy_file(test::test_signer().allowed_signers, dir_ / "allowed_signers");
    }
    // Both paths' verdicts, asserted equal; returns whether the signature holds.
    bool both(const std::string& principal, const Signed& s,
              const char* name_space = kSignatureNamespace) const {
        const auto in_process = SignatureVerifier(dir_ / "allowed_signers", name_space)
                                    .verify(principal, s.message, s.signature);
        const auto by_ssh_keygen = SignatureVerifier(dir_ / "allowed_signers", name_space)
                                       .ssh_keygen_only()
                                       .verify(principal, s.message, s.signature);
        EXPECT_EQ(bool(in_process), bool(by_ssh_keygen))
            << (in_process ? by_ssh_keygen.error().message : in_process.error().message);
        if (!in_process && !by_ssh_keygen) {
            EXPECT_EQ(in_process.error().message, by_ssh_keygen.error().message)
                << "a refusal's reason comes from ssh-keygen either way";
        }
        return bool(by_ssh_keygen);
    }
    // Whether the in-process check alone decides it (true: accepted without ssh-keygen).
    bool decided_in_process(const std::string& principal, const Signed& s,
                            const char* name_space = kSignatureNamespace) const {
        const std::string allowed = test::read_file(dir_ / "allowed_signers");
        const std::string revoked = test::read_file(dir_ / "revoked_keys");
        const std::string_view revoked_view = revoked;
        return verified_in_process(allowed,
                                   fs::exists(dir_ / "revoked_keys") ? &revoked_view : nullptr,
                                   principal, name_space, s.message, s.signature);
    }
    fs::path dir_;
};

TEST_F(InProcessSignatures, AGoodSignatureIsAcceptedWithoutSshKeygen) {
    const Signed s = sign_as(test::test_signer().key, "a statement\n", kSignatureNamespace);
    EXPECT_TRUE(both("rita@example.org", s));
    EXPECT_TRUE(decided_in_process("rita@example.org", s));
    // Every name the line lists.
    EXPECT_TRUE(decided_in_process("pat@example.org", s));
}

TEST_F(InProcessSignatures, EveryKindOfBadSignatureIsRefusedByBoth) {
    const Signed good = sign_as(test::test_signer().key, "a statement\n", kSignatureNamespace);
    // Another name than the key's line lists.
    EXPECT_FALSE(both("eve@example.org", good));
    EXPECT_FALSE(decided_in_process("eve@example.org", good));
    // Other content.
    const Signed altered{"another statement\n", good.signature};
    EXPECT_FALSE(both("rita@example.org", altered));
    EXPECT_FALSE(decided_in_process("rita@example.org", altered));
    // A key no line lists.
    const Signed stranger =
        sign_as(test::test_signer().unlisted_key, "a statement\n", kSignatureNamespace);
    EXPECT_FALSE(both("rita@example.org", stranger));
    EXPECT_FALSE(decided_in_process("rita@example.org", stranger));
    // A key listed for another namespace: the runner's, whose line allows case results only.
    const Signed runner =
        sign_as(test::test_signer().runner_key, "a statement\n", kSignatureNamespace);
    EXPECT_FALSE(both(test::kTestRunnerName, runner));
    EXPECT_FALSE(decided_in_process(test::kTestRunnerName, runner));
    // Signed in one namespace, checked in another.
    EXPECT_FALSE(both("rita@example.org", good, kCaseResultNamespace));
    EXPECT_FALSE(decided_in_process("rita@example.org", good, kCaseResultNamespace));
    // Not a signature at all, and a truncated one.
    EXPECT_FALSE(both("rita@example.org", {good.message, "not a signature\n"}));
    const std::string cut =
        good.signature.substr(0, good.signature.size() / 2) + "\n-----END SSH SIGNATURE-----\n";
    EXPECT_FALSE(both("rita@example.org", {good.message, cut}));
    EXPECT_FALSE(decided_in_process("rita@example.org", {good.message, cut}));
}

TEST_F(InProcessSignatures, ARevokedKeyIsRefusedByBoth) {
    const Signed good = sign_as(test::test_signer().key, "a statement\n", kSignatureNamespace);
    test::write_text(dir_ / "revoked_keys",
                     "# revoked\n" + test::read_file(test::test_signer().public_key));
    EXPECT_FALSE(both("rita@example.org", good));
    EXPECT_FALSE(decided_in_process("rita@example.org", good));
    // Revocations of other keys leave it standing, still decided in process.
    test::write_text(dir_ / "revoked_keys",
                     test::read_file(fs::path(test::test_signer().unlisted_key.string() + ".pub")));
    EXPECT_TRUE(both("rita@example.org", good));
    EXPECT_TRUE(decided_in_process("rita@example.org", good));
}

// A file the in-process check does not fully read (here a certificate authority line) is left
// to ssh-keygen, which still accepts a good signature.
TEST_F(InProcessSignatures, AFileWithOptionsItDoesNotReadIsLeftToSshKeygen) {
    const Signed good = sign_as(test::test_signer().key, "a statement\n", kSignatureNamespace);
    std::string allowed = test::read_file(dir_ / "allowed_signers");
    allowed += "*@ca.example.org cert-authority " +
               test::read_file(fs::path(test::test_signer().unlisted_key.string() + ".pub"));
    test::write_text(dir_ / "allowed_signers", allowed);
    EXPECT_FALSE(decided_in_process("rita@example.org", good));
    EXPECT_TRUE(both("rita@example.org", good));
}

}  // namespace
}  // namespace acetate
