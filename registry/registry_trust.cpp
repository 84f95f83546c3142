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
    // Who is an outside author, read once; scopes that cannot be read trust nothing, as an
    // unreadable revocation list does.
    auto scopes = verifier.read_author_scopes();
    for (RegistryEntry& e : entries_) {
        if (which && !which(e)) continue;
        auto drop = [&](const char* what, std::optional<SignOff>& s, const std::string& why) {
            e.distrusted[what] = fmt::format("the {} by {} is not trusted: {}", what, s->by, why);
            s.reset();
        };
        auto check = [&](const char* what, std::optional<SignOff>& s, ValidationStage grants) {
            if (!s) return;
            if (!scopes)
                return drop(what, s, "its signature cannot be checked: " + scopes.error().message);
            auto verified = verifier.verify(s->by, sign_off_statement(e.id, e.version, grants, *s),
                                            s->signature);
            if (!verified) return drop(what, s, "its signature " + verified.error().message);
            if (scopes->is_author(s->by) && !scopes->covers(s->by, e.id))
                return drop(
                    what, s,
                    fmt::format("{} is an outside author who may sign for {} only ({})", s->by,
                                scopes->patterns_of(s->by), verifier.author_scopes().string()));
            // A plugin's own author vouches for its code, never for its promotion: VALIDATED
            // needs an independent maintainer's signature.
            if (grants == ValidationStage::Validated && scopes->covers(s->by, e.id))
                return drop(what, s,
                            fmt::format("{} is the plugin's own author; VALIDATED needs a "
                                        "promotion by an independent maintainer",
                                        s->by));
            if (grants == ValidationStage::Reviewed)
                e.review_by_author = scopes->covers(s->by, e.id);
        };
        check("review", e.review, ValidationStage::Reviewed);
        check("promotion", e.promotion, ValidationStage::Validated);
    }
}

}  // namespace acetate
