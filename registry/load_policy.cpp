#include "load_policy.hpp"

#include <fmt/format.h>

#include "core/input_file.hpp"
#include "registry.hpp"
#include "registry_location.hpp"
#include "registry_scan.hpp"
#include "ssh_signature.hpp"

namespace acetate {

Result<LoadPolicy> LoadPolicy::open(LoadPolicyOptions options) {
    LoadPolicy policy;
    const std::filesystem::path file = registry_path(options.registry);
    // A missing file: nothing is validated.
    auto bytes = read_input_file_if_exists(file, kMaxRegistryFileBytes, "a registry");
    if (!bytes) return bytes.error();
    policy.registry_text_ = std::make_shared<const std::string>(bytes->value_or(std::string()));
    policy.registry_file_ = file.string();
    // A file that is not a registry at all is refused now, before anything loads, with the
    // full reader's message; its entries are read as admissions need them.
    if (bytes->has_value() && !scan_registry(**bytes))
        if (auto whole = Registry::parse(**bytes, policy.registry_file_); !whole)
            return whole.error();
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
    // Only the entries of this binary and this id are read: what the refusal explains, and
    // all that can admit it.
    auto selected = registry_text_->empty()
                        ? Result<Registry>(Registry())
                        : Registry::parse_selected(
                              *registry_text_, registry_file_, [&](std::string_view entry) {
                                  return entry.find(sha.value()) != std::string_view::npos ||
                                         (!id.empty() &&
                                          entry.find("\"" + id + "\"") != std::string_view::npos);
                              });
    if (!selected) return selected.error();
    Registry trusted = std::move(selected).value();
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
