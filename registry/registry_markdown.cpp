// VALIDATION-REGISTRY.md: the registry rendered for people (registry.hpp). Generated, never
// read back: registry.json is the record.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/atomic_file.hpp"
#include "registry.hpp"
#include "registry_fields.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using registry_fields::short_hash;

// ---- Markdown -------------------------------------------------------------------------------

// One line, safe inside a table cell.
std::string cell(std::string_view s) {
    std::string out;
    for (char c : s) {
        if (c == '|')
            out += "\\|";
        else if (c == '\n' || c == '\r')
            out += ' ';
        else
            out += c;
    }
    return out;
}

std::string who_when(const std::optional<SignOff>& s) {
    return s ? cell(fmt::format("{}, {}", s->by, s->at)) : "—";
}

std::string when_harness(const std::optional<StageEvidence>& ev) {
    return ev ? cell(fmt::format("{} (harness {})", ev->at, ev->harness_version)) : "—";
}

std::string counts_text(const StageEvidence& ev) {
    std::vector<std::string> parts;
    for (const auto& [verdict, n] : ev.counts) parts.push_back(fmt::format("{} {}", n, verdict));
    return parts.empty() ? "no counts" : fmt::format("{}", fmt::join(parts, ", "));
}

std::string waiver_text(const Waiver& w) {
    return fmt::format("{} until {}, by {} at {}: {}", w.check, w.until, w.by, w.at, w.reason);
}

}  // namespace

// ---- VALIDATION-REGISTRY.md -----------------------------------------------------------------

std::string render_registry_markdown(const Registry& registry, std::string_view source_name) {
    std::string out = fmt::format(
        "# Validation registry\n\n"
        "Generated from `{}` by acetate-harness; do not edit by hand. Stages: UNVALIDATED → "
        "REVIEWED → ALPHA_TESTED → INTEGRATED → VALIDATED, never skipped; what each promises is "
        "in docs/registry.md. Sign-offs bind to the source digest, evidence to the binary's "
        "SHA-256 (both shortened to 12 digits here).\n\n",
        source_name);
    if (registry.entries().empty()) return out + "No plugins recorded yet.\n";

    out +=
        "| Plugin | Version | Stage | Binary SHA-256 | Source digest | Reviewed | "
        "Alpha-tested | Integrated | Promoted |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
    for (const RegistryEntry& e : registry.entries())
        out += fmt::format("| `{}` | {} | **{}** | `{}` | `{}` | {} | {} | {} | {} |\n", e.id,
                           e.version, to_string(e.stage()), short_hash(e.binary_sha256),
                           short_hash(e.source_digest), who_when(e.review),
                           when_harness(e.alpha_tested), when_harness(e.integrated),
                           who_when(e.promotion));

    for (const RegistryEntry& e : registry.entries()) {
        out += fmt::format("\n## {} {} — {}\n\n", e.id, e.version, to_string(e.stage()));
        out += fmt::format("- Binary SHA-256 `{}`, source digest `{}`\n", e.binary_sha256,
                           e.source_digest);
        auto sign_off = [&](const char* what, const std::optional<SignOff>& s) {
            if (s)
                out += cell(fmt::format("- {} by {} at {}: {}", what, s->by, s->at,
                                        s->notes.empty() ? "(no notes)" : s->notes)) +
                       "\n";
        };
        auto evidence = [&](const char* what, const std::optional<StageEvidence>& ev) {
            if (!ev) return;
            out +=
                cell(fmt::format("- {} at {}, harness {}: {}{}", what, ev->at, ev->harness_version,
                                 ev->summary.empty() ? "" : ev->summary + "; ", counts_text(*ev)));
            if (!ev->report.empty()) out += cell(fmt::format("; report `{}`", ev->report));
            if (ev->strictness > 0) out += fmt::format("; strictness {}", ev->strictness);
            if (ev->seed) out += fmt::format(", seed {}", *ev->seed);
            out += "\n";
        };
        sign_off("Reviewed", e.review);
        evidence("Alpha-tested", e.alpha_tested);
        evidence("Integrated", e.integrated);
        sign_off("Promoted to VALIDATED", e.promotion);
        for (const Waiver& w : e.waivers) out += cell("- Waived: " + waiver_text(w)) + "\n";
    }
    return out;
}

Result<void> write_registry_markdown(const Registry& registry, const fs::path& file,
                                     std::string_view source_name) {
    return write_file_atomically(file, render_registry_markdown(registry, source_name));
}

}  // namespace acetate
