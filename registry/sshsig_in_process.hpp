#pragma once
// SSH signatures checked in this process: the common case of SignatureVerifier (an Ed25519 key
// on a plain allowed-signers line) decided with libcrypto in microseconds instead of an
// ssh-keygen process per signature, so a registry of thousands of sign-offs is read in well
// under a second. The format is OpenSSH's PROTOCOL.sshsig.
//
// It only ever says yes when `ssh-keygen -Y verify` would: any file it does not fully
// understand (a principal or namespace pattern, a `cert-authority` or `valid-*` option, quoted
// principals, a binary KRL for revocations) and any signature it does not accept is left to
// ssh-keygen, which also gives the reasons for a refusal. tests/unit/sshsig_in_process_test.cpp
// holds the two paths side by side.

#include <string_view>

namespace acetate {

// True when `armored` is a good Ed25519 signature of `message` in `name_space`, made by a key
// that `allowed_signers` lists for `principal` (for that namespace) and that `revoked_keys`
// (nullptr: none) does not list. False means "not decided here": ask ssh-keygen.
bool verified_in_process(std::string_view allowed_signers, const std::string_view* revoked_keys,
                         std::string_view principal, std::string_view name_space,
                         std::string_view message, std::string_view armored);

}  // namespace acetate
