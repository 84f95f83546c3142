#include "validate_registry.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "registry_location.hpp"
#include "ssh_signature.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;

std::map<std::string, uint64_t> verdict_counts(const std::vector<CaseResult>& results) {
    std::map<std::string, uint64_t> counts;
    for (const CaseResult& r : results) ++counts[to_string(r.verdict)];
    return counts;
}

}  // namespace

Result<RegistryTransaction> RegistryTransaction::open(fs::path file) {
    auto loaded = Registry::load(file);  // a missing file: nothing recorded yet
    if (!loaded) return loaded.error();
    RegistryTransaction t;
    t.file_ = std::move(file);
    t.view_ = std::move(loaded).value();
    return t;
}

Result<void> RegistryTransaction::apply(std::function<Result<void>(Registry&)> change) {
    Registry changed = view_;
    ACETATE_TRY(change(changed));
    view_ = std::move(changed);
    changes_.push_back(std::move(change));
    return {};
}

Result<void> RegistryTransaction::commit() const {
    if (changes_.empty()) return {};
    return Registry::update(
        file_,
        [&](Registry& r) -> Result<void> {
            for (const auto& change : changes_) ACETATE_TRY(change(r));
            return {};
        },
        registry_markdown_path(file_));
}

Result<void> record(RegistryTransaction& registry, const ValidateOptions& o,
                    const PluginInfo& plugin, ValidationStage stage,
                    const std::vector<CaseResult>& results, const std::string& report,
                    const std::vector<CompanionPlugin>& companions) {
    StageEvidence evidence;
    evidence.harness_version = kHarnessVersion;
    evidence.counts = verdict_counts(results);
    evidence.report = report;
    evidence.strictness = o.strictness;
    evidence.seed = o.seed;
    const uint64_t waived = evidence.counts.count("WAIVED") ? evidence.counts.at("WAIVED") : 0;
    evidence.summary = fmt::format("{} cases at strictness {}, seed {}: all passed{}",
                                   results.size(), o.strictness, o.seed,
                                   waived ? fmt::format(" ({} under a waiver)", waived) : "");
    if (stage == ValidationStage::Integrated) {
        std::vector<std::string> ids;
        for (const CompanionPlugin& c : companions) ids.push_back(c.id);
        evidence.summary += ids.empty() ? "; no other integrated plugin yet"
                                        : fmt::format("; with {}", fmt::join(ids, ", "));
    }
    return registry.apply([plugin, stage, evidence](Registry& r) {
        return r.record_evidence(plugin.id, plugin.version, plugin.binary_sha256,
                                 plugin.source_digest, stage, evidence);
    });
}

Result<std::vector<std::string>> import_committed(RegistryTransaction& registry,
                                                  const ValidateOptions& o,
                                                  const PluginInfo& plugin) {
    if (!o.signoffs) return std::vector<std::string>{};
    auto signoffs = Registry::load(*o.signoffs);
    if (!signoffs) return signoffs.error();
    const SignatureVerifier verifier(o.allowed_signers);
    signoffs->verify_sign_offs(verifier, entry_of(plugin.id, plugin.version));
    std::vector<std::string> lines, imported;
    if (const RegistryEntry* committed = signoffs->find(plugin.id, plugin.version))
        for (const auto& [what, why] : committed->distrusted)
            lines.push_back(fmt::format("not imported from {}: {}", o.signoffs->string(), why));
    Registry preview = registry.view();
    imported = import_signoffs(preview, signoffs.value(), plugin, verifier);
    if (!imported.empty())
        ACETATE_TRY(registry.apply(
            [committed = signoffs.value(), plugin, verifier](Registry& r) -> Result<void> {
                import_signoffs(r, committed, plugin, verifier);
                return {};
            }));
    for (const std::string& line : imported)
        lines.push_back(
            line.rfind("nothing: ", 0) == 0
                ? fmt::format("not imported from {}: {}", o.signoffs->string(), line.substr(9))
                : fmt::format("imported the committed {} from {}", line, o.signoffs->string()));
    return lines;
}

std::vector<HistoryLine> history_of(const Registry& registry, const PluginInfo& plugin) {
    std::vector<HistoryLine> lines;
    const RegistryEntry* e = registry.find(plugin.id, plugin.version);
    if (!e) return lines;
    if (e->review)
        lines.push_back({e->review->at, "review (REVIEWED)", e->review->by, e->review->notes});
    if (e->alpha_tested)
        lines.push_back({e->alpha_tested->at, "ALPHA_TESTED evidence",
                         e->alpha_tested->harness_version, e->alpha_tested->summary});
    if (e->integrated)
        lines.push_back({e->integrated->at, "INTEGRATED evidence", e->integrated->harness_version,
                         e->integrated->summary});
    if (e->promotion)
        lines.push_back(
            {e->promotion->at, "promotion (VALIDATED)", e->promotion->by, e->promotion->notes});
    return lines;
}

ValidationStage current_stage(const Registry& registry, const ValidateOptions& o,
                              const PluginInfo& p) {
    Registry verified = registry;
    verified.verify_sign_offs(SignatureVerifier(o.allowed_signers), entry_of(p.id, p.version));
    return verified.effective_stage(p.id, p.version, p.binary_sha256, p.source_digest);
}

std::vector<std::string> import_signoffs(Registry& registry, const Registry& signoffs,
                                         const PluginInfo& p, const SignatureVerifier& verifier) {
    std::vector<std::string> imported;
    const RegistryEntry* committed = signoffs.find(p.id, p.version);
    if (!committed) return imported;
    // The stage the registry's own sign-offs support once verified: an unsigned or forged
    // review there does not keep the committed one out.
    auto trusted_stage = [&] {
        Registry view = registry;
        view.verify_sign_offs(verifier, entry_of(p.id, p.version));
        return view.effective_stage(p.id, p.version, p.binary_sha256, p.source_digest);
    };
    if (committed->review && committed->review->source_digest == p.source_digest &&
        trusted_stage() == ValidationStage::Unvalidated &&
        registry.record_review(p.id, p.version, p.binary_sha256, p.source_digest,
                               *committed->review))
        imported.push_back(
            fmt::format("review by {} ({})", committed->review->by, committed->review->at));
    if (committed->promotion && committed->promotion->source_digest == p.source_digest &&
        trusted_stage() == ValidationStage::Integrated) {
        if (auto promoted = registry.promote(p.id, p.version, *committed->promotion))
            imported.push_back(fmt::format("promotion by {} ({})", committed->promotion->by,
                                           committed->promotion->at));
        else
            imported.push_back(fmt::format("nothing: the promotion by {}: {}",
                                           committed->promotion->by, promoted.error().message));
    }
    return imported;
}

}  // namespace acetate::harness
