#pragma once
// A maintainer for tests: an SSH key made once per test process, and an allowed-signers file
// that lists it (after the committed validation/allowed_signers) for the names tests sign as.
// The harness and the host read both through the environment (signer_environment()).

#include <filesystem>
#include <string>

#include "registry.hpp"

namespace acetate::test {

struct TestSigner {
    std::filesystem::path key;              // private key, mode 0600
    std::filesystem::path public_key;       // key.pub
    std::filesystem::path allowed_signers;  // the committed lines, then this key's
    std::filesystem::path unlisted_key;     // a second key no allowed-signers line names
    // A shard runner's key: listed for kTestRunnerName in the case-result namespace only, so
    // it signs results and cannot sign a sign-off.
    std::filesystem::path runner_key;
};

inline constexpr const char* kTestRunnerName = "runner@example.org";

// The names the test key signs for.
inline constexpr const char* kTestSignerNames =
    "rita@example.org,pat@example.org,maintainers@example.org,policy-test@example.org";

// Made on first use in a private temporary folder, removed when the process exits.
const TestSigner& test_signer();

// "ACETATE_ALLOWED_SIGNERS='…' ACETATE_SIGNING_KEY='…' ACETATE_RUNNER='…'
// ACETATE_RUNNER_KEY='…'" for a command line.
std::string signer_environment();

// Signs `s` as granting `stage` to the plugin, with `key` (the test key by default).
void sign(SignOff& s, const std::string& id, const std::string& version, ValidationStage stage,
          const std::filesystem::path& key = {});

}  // namespace acetate::test
