#pragma once
// Maintainers' signatures, made and checked by OpenSSH's `ssh-keygen -Y sign` and `-Y verify`
// (the scheme git uses for signed commits) in the namespace "acetate-signoff". A signature is
// the armored text ssh-keygen writes ("-----BEGIN SSH SIGNATURE-----" ...); what is signed is a
// sign-off's statement (sign_off_statement in registry.hpp). Which key may sign for which
// maintainer is an allowed-signers file (ssh-keygen(1), "ALLOWED SIGNERS"), committed as
// validation/allowed_signers; a key listed in the file `revoked_keys` beside it is refused even
// where it is allowed. docs/registry.md, "Signatures", has the maintainer's side.
//
// Both run ssh-keygen as a child process with a private temporary folder, so a key's
// passphrase prompt (or an agent) works as it does for git. Errors are one line: Io when
// ssh-keygen cannot run or the key cannot be used, InvalidInput when a signature does not hold.

#include <filesystem>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace acetate {

inline constexpr const char* kSignatureNamespace = "acetate-signoff";

// Signs `message` with the private key file `key` (or the public half of a key held by
// ssh-agent, as git's user.signingkey allows). Returns the armored signature.
Result<std::string> ssh_sign(const std::filesystem::path& key, std::string_view message);

// Checks signatures against one allowed-signers file (and the revoked_keys beside it, if any).
class SignatureVerifier {
  public:
    explicit SignatureVerifier(std::filesystem::path allowed_signers);

    // Ok when `signature` is a good signature of `message`, made by a key the allowed-signers
    // file lists for `principal`, and not revoked. Otherwise InvalidInput saying why in a few
    // words ("made by a key not allowed for NAME", "does not match what it claims to sign",
    // "is missing", "made by a revoked key"), or Io when the files or ssh-keygen are missing.
    Result<void> verify(std::string_view principal, std::string_view message,
                        std::string_view signature) const;

    const std::filesystem::path& allowed_signers() const { return allowed_signers_; }
    // validation/revoked_keys beside the allowed-signers file (it may not exist).
    std::filesystem::path revoked_keys() const;

  private:
    std::filesystem::path allowed_signers_;
};

}  // namespace acetate
