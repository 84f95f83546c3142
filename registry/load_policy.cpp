#include "load_policy.hpp"

#include <fmt/format.h>

#include "registry.hpp"
#include "registry_location.hpp"
#include "ssh_signature.hpp"

namespace acetate {

Result<LoadPolicy> LoadPolicy::open(LoadPolicyOptions options) {
    LoadPolicy policy;
    const std::filesystem::path file = registry_path(options.registry);
    auto loaded = Registry::load(file);  // a missing file: nothing is validated
    if (!loaded) return loaded.error();
    policy.registry_ = std::make_shared<const Registry>(std::move(loaded).value());
    std::error_code ec;
    policy.registry_name_ = fmt::format("registry {}{}", file.string(),
                                        std::filesystem::exists(file, ec) ? "" : " (no such file)");
    policy.allowed_signers_ = allowed_signers_path(options.allowed_signers);
    policy.options_ = std::move(options);
    return policy;
}

Result<void> LoadPolicy::admit(const std::string& id, const std::filesystem::path& file,
                               const std::filesystem::path& contents) const {
    auto sha = file_sha256(contents);  // the open file that will be loaded, not the path
    if (!sha) return sha.error();
    // Only this binary's entries are verified: each verification runs ssh-keygen.
    Registry trusted = *registry_;
    trusted.verify_sign_offs(SignatureVerifier(allowed_signers_), [&](const RegistryEntry& e) {
        return e.binary_sha256 == sha.value() && (id.empty() || e.id == id);
    });
    if (trusted.binary_stage(id, sha.value()) == ValidationStage::Validated) return {};
    const std::string plugin =
        id.empty() ? file.string() : fmt::format("{} ({})", id, file.string());
    const std::string why =
        fmt::format("not VALIDATED for this binary (SHA-256 {}): {}: {}", sha->substr(0, 12),
                    registry_name_, trusted.explain(id, *sha));
    if (options_.allow_unvalidated) {
        const std::string line =
            fmt::format("warning: loading unvalidated plugin {}: {}", plugin, why);
        if (options_.warn)
            options_.warn(line);
        else
            std::fprintf(stderr, "%s\n", line.c_str());
        return {};
    }
    return make_error(ErrorCode::InvalidInput,
                      fmt::format("{} is {}; run acetate-harness validate {}, or {}", plugin, why,
                                  file.string(), options_.allow_hint));
}

}  // namespace acetate
