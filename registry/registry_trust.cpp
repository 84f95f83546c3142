// Which sign-offs a registry reader may trust: each is a maintainer's SSH signature over its
// statement, checked against the allowed signers (ssh_signature.hpp, docs/registry.md,
// "Signatures").

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "registry.hpp"
#include "ssh_signature.hpp"

namespace acetate {

std::string sign_off_statement(std::string_view id, std::string_view version, ValidationStage stage,
                               const SignOff& s) {
    // Ordered and compact, so the same sign-off always gives the same bytes to sign.
    const nlohmann::ordered_json statement = {{"format", "acetate-signoff/1"},
                                              {"plugin", id},
                                              {"version", version},
                                              {"stage", to_string(stage)},
                                              {"source_digest", s.source_digest},
                                              {"by", s.by},
                                              {"at", s.at},
                                              {"notes", s.notes}};
    return statement.dump() + "\n";
}

std::function<bool(const RegistryEntry&)> entry_of(std::string_view id, std::string_view version) {
    return [id = std::string(id), version = std::string(version)](const RegistryEntry& e) {
        return e.id == id && e.version == version;
    };
}

void Registry::verify_sign_offs(const SignatureVerifier& verifier,
                                const std::function<bool(const RegistryEntry&)>& which) {
    for (RegistryEntry& e : entries_) {
        if (which && !which(e)) continue;
        auto check = [&](const char* what, std::optional<SignOff>& s, ValidationStage grants) {
            if (!s) return;
            auto verified = verifier.verify(s->by, sign_off_statement(e.id, e.version, grants, *s),
                                            s->signature);
            if (verified) return;
            e.distrusted[what] = fmt::format("the {} by {} is not trusted: its signature {}", what,
                                             s->by, verified.error().message);
            s.reset();
        };
        check("review", e.review, ValidationStage::Reviewed);
        check("promotion", e.promotion, ValidationStage::Validated);
    }
}

}  // namespace acetate
