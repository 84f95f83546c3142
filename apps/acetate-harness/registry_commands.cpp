#include "registry_commands.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "references.hpp"
#include "registry_fields.hpp"
#include "registry_location.hpp"
#include "waivers.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;

int fail(const std::string& message) {
    std::fprintf(stderr, "acetate-harness: %s\n", message.c_str());
    return 1;
}

// The registry as a host would trust it: loaded, then the sign-offs of the entries `which`
// selects verified (every entry when empty).
Result<Registry> load_trusted(const RegistryCommandContext& c,
                              const std::function<bool(const RegistryEntry&)>& which = {}) {
    auto loaded = Registry::load(c.registry);
    if (!loaded) return loaded.error();
    loaded->verify_sign_offs(c.verifier, which);
    return loaded;
}

// Signs `s` as granting `stage` to the plugin, with the maintainer's key, and checks the
// signature as every reader will: a key the allowed signers do not list for `s.by` is refused
// here, before anything is recorded.
Result<void> sign(const RegistryCommandContext& c, const PluginInfo& p, ValidationStage stage,
                  SignOff& s) {
    const char* what = stage == ValidationStage::Reviewed ? "review" : "promotion";
    const std::string plugin = fmt::format("{} {}", p.id, p.version);
    if (registry_fields::is_blank(s.by))
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{}: {} refused: the {}'s name is empty (a sign-off says "
                        "who signed)",
                        plugin, what,
                        stage == ValidationStage::Reviewed ? "reviewer" : "maintainer"));
    if (!c.signing_key)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: {} refused: no signing key; pass --key FILE (your SSH "
                                      "private key, or its .pub with ssh-agent) or set "
                                      "ACETATE_SIGNING_KEY: sign-offs are SSH signatures",
                                      plugin, what));
    const std::string statement = sign_off_statement(p.id, p.version, stage, s);
    auto signature = ssh_sign(*c.signing_key, statement);
    if (!signature)
        return make_error(ErrorCode::Io, fmt::format("{}: {} refused: {}", plugin, what,
                                                     signature.error().message));
    if (auto held = c.verifier.verify(s.by, statement, *signature); !held)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: {} refused: this signature {}; {} lists which key "
                                      "signs for {} (reviewed like code)",
                                      plugin, what, held.error().message,
                                      c.verifier.allowed_signers().string(), s.by));
    // The author scopes, as every reader applies them (registry_trust.cpp): an outside author
    // signs for their own plugins only, and never their promotion.
    auto scopes = c.verifier.read_author_scopes();
    if (!scopes)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: {} refused: {}", plugin, what, scopes.error().message));
    if (scopes->is_author(s.by) && !scopes->covers(s.by, p.id))
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: {} refused: {} is an outside author who may sign for "
                                      "{} only ({})",
                                      plugin, what, s.by, scopes->patterns_of(s.by),
                                      c.verifier.author_scopes().string()));
    if (stage == ValidationStage::Validated && scopes->covers(s.by, p.id))
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: promotion refused: {} is the plugin's own author; "
                                      "VALIDATED needs a promotion by an independent maintainer",
                                      plugin, s.by));
    s.signature = std::move(signature).value();
    return {};
}

// What a maintainer must see before promoting `entry`: every waiver, and evidence taken below
// the default strictness, one indented line each.
void print_waivers_and_strictness(const RegistryEntry& entry) {
    for (const std::string& line : waiver_lines(entry.waivers, utc_today()))
        std::printf("    waiver: %s\n", line.c_str());
    auto strictness = [](const char* stage, const std::optional<StageEvidence>& ev) {
        if (ev && ev->strictness > 0 && ev->strictness < kDefaultStrictness)
            std::printf("    %s evidence at strictness %d, below the default %d\n", stage,
                        ev->strictness, kDefaultStrictness);
    };
    strictness("ALPHA_TESTED", entry.alpha_tested);
    strictness("INTEGRATED", entry.integrated);
}

}  // namespace

// The golden references a reviewer reads with the source: blessed for this source, for another
// one (stale), or none.
static void print_references(const PluginInfo& p, const fs::path& root) {
    auto set = load_references(root, p.id);
    if (!set) {
        std::printf("    references: %s\n", set.error().message.c_str());
    } else if (!set.value()) {
        std::printf("    references: none blessed in %s (acetate-harness bless %s --by NAME)\n",
                    (root / p.id).string().c_str(), p.file.c_str());
    } else {
        const ReferenceSet& r = *set.value();
        std::printf(
            "    references: %zu images blessed by %s at %s for source %s%s; look at "
            "them with the source:\n",
            r.images.size(), r.blessed_by.c_str(), r.at.c_str(),
            r.source_digest.substr(0, 12).c_str(),
            r.source_digest == p.source_digest ? "" : " (another source: bless again)");
        for (const auto& [id, name] : r.images)
            std::printf("      %-28s %s\n", id.c_str(), (r.directory / name).string().c_str());
    }
}

int run_review(const PluginInfo& p, const RegistryCommandContext& c,
               const SignOffRequest& request) {
    print_references(p, c.references);
    SignOff review{request.by, utc_now_iso8601(), request.notes, p.source_digest, ""};
    if (auto signed_ok = sign(c, p, ValidationStage::Reviewed, review); !signed_ok)
        return fail(signed_ok.error().message);
    auto updated = Registry::update(
        c.registry,
        [&](Registry& r) {
            return r.record_review(p.id, p.version, p.binary_sha256, p.source_digest, review);
        },
        registry_markdown_path(c.registry));
    if (!updated) return fail(updated.error().message);
    auto trusted = load_trusted(c, entry_of(p.id, p.version));
    const ValidationStage stage =
        trusted ? trusted->effective_stage(p.id, p.version, p.binary_sha256, p.source_digest)
                : ValidationStage::Reviewed;
    std::printf("%s %s: review by %s signed and recorded for source %s; now %s (registry %s)\n",
                p.id.c_str(), p.version.c_str(), request.by.c_str(),
                p.source_digest.substr(0, 12).c_str(), to_string(stage),
                c.registry.string().c_str());
    return 0;
}

int run_promote(const PluginInfo& p, const RegistryCommandContext& c,
                const SignOffRequest& request) {
    // The promotion vouches for this file: it must be the binary the evidence is for, and the
    // earlier sign-offs must hold as a host will check them.
    auto trusted = load_trusted(c, entry_of(p.id, p.version));
    if (!trusted) return fail(trusted.error().message);
    const RegistryEntry* entry = trusted->find(p.id, p.version);
    // Every waiver and any evidence below the default strictness, whatever the outcome: the
    // maintainer vouches for them too.
    if (entry) print_waivers_and_strictness(*entry);
    const ValidationStage stage =
        trusted->effective_stage(p.id, p.version, p.binary_sha256, p.source_digest);
    if (stage == ValidationStage::Validated) {
        std::printf(
            "%s %s: already VALIDATED for this binary (promoted by %s at %s); nothing "
            "recorded\n",
            p.id.c_str(), p.version.c_str(), entry->promotion->by.c_str(),
            entry->promotion->at.c_str());
        return 0;
    }
    if (stage != ValidationStage::Integrated) {
        std::string why = fmt::format("{} {}: this binary (SHA-256 {}) is {}, not INTEGRATED", p.id,
                                      p.version, p.binary_sha256.substr(0, 12), to_string(stage));
        if (entry && !entry->distrusted.empty()) why += ": " + entry->distrusted.begin()->second;
        return fail(fmt::format("{}: run acetate-harness validate {} first", why, p.file));
    }
    SignOff promotion{request.by, utc_now_iso8601(), request.notes, p.source_digest, ""};
    // Refusals that need no key come first (an expired waiver, low strictness).
    {
        Registry dry_run = *trusted;
        if (auto ok = dry_run.promote(p.id, p.version, promotion); !ok)
            return fail(ok.error().message);
    }
    if (auto signed_ok = sign(c, p, ValidationStage::Validated, promotion); !signed_ok)
        return fail(signed_ok.error().message);
    auto updated = Registry::update(
        c.registry, [&](Registry& r) { return r.promote(p.id, p.version, promotion); },
        registry_markdown_path(c.registry));
    if (!updated) return fail(updated.error().message);
    std::printf("%s %s: promoted to VALIDATED by %s, signed (registry %s)\n", p.id.c_str(),
                p.version.c_str(), request.by.c_str(), c.registry.string().c_str());
    return 0;
}

int run_waive(const PluginInfo& p, const RegistryCommandContext& c, const WaiveRequest& request) {
    const auto& known = waivable_checks();
    if (std::find(known.begin(), known.end(), request.check) == known.end())
        return fail(fmt::format("waive: \"{}\" is not a check a waiver may name ({})",
                                request.check, fmt::join(known, ", ")));
    // A waiver is granted on reviewed code: the review must hold as a host checks it.
    auto trusted = load_trusted(c, entry_of(p.id, p.version));
    if (!trusted) return fail(trusted.error().message);
    Waiver waiver{request.check, request.reason, request.by, "", request.until, ""};
    if (auto ok =
            Registry(*trusted).waive(p.id, p.version, p.binary_sha256, p.source_digest, waiver);
        !ok)
        return fail(ok.error().message);
    auto updated = Registry::update(
        c.registry,
        [&](Registry& r) {
            return r.waive(p.id, p.version, p.binary_sha256, p.source_digest, waiver);
        },
        registry_markdown_path(c.registry));
    if (!updated) return fail(updated.error().message);
    std::printf(
        "%s %s: \"%s\" waived until %s by %s for source %s (registry %s); it reads WAIVED, "
        "never PASS\n",
        p.id.c_str(), p.version.c_str(), request.check.c_str(), request.until.c_str(),
        request.by.c_str(), p.source_digest.substr(0, 12).c_str(), c.registry.string().c_str());
    return 0;
}

int run_status(const RegistryCommandContext& c, bool as_json) {
    auto registry = load_trusted(c);
    if (!registry) return fail(registry.error().message);
    if (as_json) {
        // The file as written, with each entry's stage as the verified records support it.
        auto raw = Registry::load(c.registry);
        auto j = nlohmann::json::parse(raw->to_json());
        j["registry"] = c.registry.string();
        j["allowed_signers"] = c.verifier.allowed_signers().string();
        for (auto& entry : j["plugins"]) {
            const RegistryEntry* e =
                registry->find(entry["id"].get<std::string>(), entry["version"].get<std::string>());
            if (!e) continue;
            entry["stage"] = to_string(e->stage());
            if (!e->distrusted.empty()) entry["distrusted"] = e->distrusted;
            if (e->review) entry["review_by_author"] = e->review_by_author;
        }
        std::printf("%s\n", j.dump(2).c_str());
        return 0;
    }
    std::printf("registry %s (sign-offs verified with %s)\n", c.registry.string().c_str(),
                c.verifier.allowed_signers().string().c_str());
    if (registry->entries().empty()) {
        std::printf("no plugins recorded yet\n");
        return 0;
    }
    std::printf("%-26s %-8s %-13s %-12s %-12s %s\n", "plugin", "version", "stage", "binary",
                "source", "records");
    for (const RegistryEntry& e : registry->entries()) {
        std::string records;
        auto add = [&](const std::string& text) {
            records += (records.empty() ? "" : "; ") + text;
        };
        if (e.review)
            add(fmt::format("reviewed by {}{} {}", e.review->by,
                            e.review_by_author ? " (the plugin's own author)" : "", e.review->at));
        if (e.alpha_tested) add(fmt::format("alpha-tested {}", e.alpha_tested->at));
        if (e.integrated) add(fmt::format("integrated {}", e.integrated->at));
        if (e.promotion) add(fmt::format("promoted by {} {}", e.promotion->by, e.promotion->at));
        std::printf("%-26s %-8s %-13s %-12s %-12s %s\n", e.id.c_str(), e.version.c_str(),
                    to_string(e.stage()), e.binary_sha256.substr(0, 12).c_str(),
                    e.source_digest.substr(0, 12).c_str(), records.c_str());
        for (const auto& [what, why] : e.distrusted)
            std::printf("    NOT TRUSTED: %s\n", why.c_str());
        print_waivers_and_strictness(e);
    }
    std::printf("readable copy: %s\n", registry_markdown_path(c.registry).string().c_str());
    return 0;
}

}  // namespace acetate::harness
