#pragma once
// The maintainers' subcommands of acetate-harness: review, promote, waive and status. Review
// and promote sign what they approve with the maintainer's SSH key (ssh_signature.hpp) and
// check that signature against the allowed signers before recording it; status shows each
// stage as a host would trust it (sign-offs verified). docs/registry.md has the workflow.

#include <filesystem>
#include <optional>
#include <string>

#include "case_spec.hpp"
#include "registry.hpp"
#include "ssh_signature.hpp"

namespace acetate::harness {

// What every maintainer's subcommand works with.
struct RegistryCommandContext {
    std::filesystem::path registry;
    SignatureVerifier verifier;
    // --key, else $ACETATE_SIGNING_KEY: the maintainer's SSH key (review and promote).
    std::optional<std::filesystem::path> signing_key;
    // The golden references' root: review lists the images blessed for the plugin.
    std::filesystem::path references;
};

struct SignOffRequest {
    std::string by, notes;
};

struct WaiveRequest {
    std::string check, reason, until, by;
};

// Each returns the exit status and prints one line on success, one error line on failure.
int run_review(const PluginInfo& plugin, const RegistryCommandContext& context,
               const SignOffRequest& request);
int run_promote(const PluginInfo& plugin, const RegistryCommandContext& context,
                const SignOffRequest& request);
// Refuses a check no case evaluates (the message lists those a waiver may name).
int run_waive(const PluginInfo& plugin, const RegistryCommandContext& context,
              const WaiveRequest& request);
int run_status(const RegistryCommandContext& context, bool as_json);

}  // namespace acetate::harness
