#pragma once
// The host load policy (docs/registry.md, "Host policy"): a host loads a plugin only when the
// registry holds its id VALIDATED for exactly its binary (SHA-256), with every sign-off on
// that entry verified against the maintainers' keys. `acetate render`, the embedding API
// (acetate/host/host.hpp) and anything else that hosts plugins use this one policy, so they
// refuse the same files with the same line.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/result.hpp"

namespace acetate {

class Registry;

struct LoadPolicyOptions {
    std::optional<std::filesystem::path> registry;         // else registry_path()'s default
    std::optional<std::filesystem::path> allowed_signers;  // else allowed_signers_path()'s
    bool allow_unvalidated = false;  // admit with a warning instead of refusing
    // How a refusal says to load anyway, after "or ": "pass --allow-unvalidated" for the CLI.
    std::string allow_hint = "pass --allow-unvalidated";
    // Where the warning for an unvalidated plugin admitted goes (one line, no newline).
    std::function<void(const std::string&)> warn;
};

class LoadPolicy {
  public:
    // Reads the registry file once (a missing file: nothing is validated). A malformed one is
    // InvalidInput naming the file and the field, as the registry reader says.
    static Result<LoadPolicy> open(LoadPolicyOptions options);

    // The plugin loader's admission hook (PluginLoader::Admission): judges the open file
    // `contents` by its bytes before it is loaded. For a file loaded by path (`id` empty) any
    // plugin VALIDATED for that SHA-256 admits it. A refusal is one line naming the plugin and
    // its file, the stage the registry holds and why, and what to do.
    Result<void> admit(const std::string& id, const std::filesystem::path& file,
                       const std::filesystem::path& contents) const;

    // "registry FILE", with " (no such file)" when it was missing.
    const std::string& registry_name() const { return registry_name_; }

  private:
    LoadPolicy() = default;
    // The registry's text, read once; each admission parses only the entries of the binary and
    // id it judges (Registry::parse_selected), so start-up does not grow with the registry.
    std::shared_ptr<const std::string> registry_text_;
    std::string registry_file_;
    std::string registry_name_;
    std::filesystem::path allowed_signers_;
    LoadPolicyOptions options_;
};

}  // namespace acetate
