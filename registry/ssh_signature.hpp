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

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace acetate {

// The namespace of maintainers' sign-offs (reviews, promotions).
inline constexpr const char* kSignatureNamespace = "acetate-signoff";
// The namespace of case results a shard's runner signs (harness/shard.hpp). A runner's key is
// listed in the allowed signers with `namespaces="acetate-case-result"`, so it can sign results
// but never a sign-off.
inline constexpr const char* kCaseResultNamespace = "acetate-case-result";

// Limits on the trust path: a key file, and the allowed-signers and revoked-keys files, are
// read only when they are regular files of at most this size (a key is under 4 KiB; a list of
// a thousand keys is under 200 KiB); a signature over kMaxSignatureBytes is refused before
// ssh-keygen sees it (an Ed25519 signature is about 300 bytes, an RSA-16384 one under 3 KiB).
inline constexpr std::uint64_t kMaxKeyFileBytes = std::uint64_t(64) << 10;
inline constexpr std::uint64_t kMaxTrustFileBytes = std::uint64_t(4) << 20;
inline constexpr std::uint64_t kMaxSignatureBytes = std::uint64_t(16) << 10;
// Every ssh-keygen run is stopped after this long.
inline constexpr std::chrono::seconds kSshKeygenTimeLimit{60};

// Signs `message` with the private key file `key` (or the public half of a key held by
// ssh-agent, as git's user.signingkey allows), in `name_space`. Returns the armored signature.
// The key file must be a regular file of at most kMaxKeyFileBytes.
Result<std::string> ssh_sign(const std::filesystem::path& key, std::string_view message,
                             const char* name_space = kSignatureNamespace);

// Outside authors (the file `author_scopes` beside the allowed signers): each line is a
// principal and the plugin ids it may sign for, as comma-separated patterns where `*` matches
// any run of characters: `alice@glow.example com.glow.*`. A principal listed here is the author
// of the plugins its patterns match: its sign-offs count for those plugins only, its review of
// one is an author's review, and it cannot promote one to VALIDATED (an independent
// maintainer does). A principal not listed is a maintainer, trusted for every plugin.
class AuthorScopes {
  public:
    // One line per principal; InvalidInput naming the line otherwise.
    static Result<AuthorScopes> parse(std::string_view text, std::string_view name);
    // Whether `principal` is an outside author at all.
    bool is_author(std::string_view principal) const;
    // Whether the author `principal` may sign for `plugin_id` (its own plugins).
    bool covers(std::string_view principal, std::string_view plugin_id) const;
    // The patterns of `principal`, joined with ", ", for a message.
    std::string patterns_of(std::string_view principal) const;

  private:
    std::map<std::string, std::vector<std::string>, std::less<>> patterns_;
};

// Checks signatures against one allowed-signers file (and the revoked_keys beside it, if any).
class SignatureVerifier {
  public:
    // Checks signatures made in `name_space`: an allowed-signers line may restrict a key to
    // some namespaces (`namespaces="..."`), so a key allowed to sign case results cannot sign
    // a sign-off.
    explicit SignatureVerifier(std::filesystem::path allowed_signers,
                               const char* name_space = kSignatureNamespace);

    // Ok when `signature` is a good signature of `message`, made by a key the allowed-signers
    // file lists for `principal`, and not revoked. Otherwise InvalidInput saying why in a few
    // words ("made by a key not allowed for NAME", "does not match what it claims to sign",
    // "is missing", "made by a revoked key"), or Io when the files or ssh-keygen are missing.
    Result<void> verify(std::string_view principal, std::string_view message,
                        std::string_view signature) const;

    // Leaves every decision to ssh-keygen, the in-process check (sshsig_in_process.hpp) off:
    // for tests that hold the two side by side.
    SignatureVerifier& ssh_keygen_only() {
        in_process_ = false;
        return *this;
    }

    const std::filesystem::path& allowed_signers() const { return allowed_signers_; }
    // validation/revoked_keys beside the allowed-signers file (it may not exist).
    std::filesystem::path revoked_keys() const;
    // validation/author_scopes beside the allowed-signers file (it may not exist): outside
    // authors' principals, each with the plugin ids its key may sign for (docs/registry.md,
    // "Third-party plugins").
    std::filesystem::path author_scopes() const;
    // The scopes, read as a trust file (regular, bounded); none when the file does not exist.
    Result<AuthorScopes> read_author_scopes() const;

  private:
    std::filesystem::path allowed_signers_;
    const char* name_space_;
    bool in_process_ = true;
};

}  // namespace acetate
