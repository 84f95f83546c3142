#pragma once
// The validation registry: which plugin (id + version) has reached which validation stage, on
// whose sign-off and on what automated evidence (docs/design.md, "Validation stages", says
// why; docs/registry.md has the workflow and the file format).
//
//   UNVALIDATED -> REVIEWED -> ALPHA_TESTED -> INTEGRATED -> VALIDATED, never skipped.
//
// A stage is never stored as a bare claim: it is derived from the records that prove it.
//   REVIEWED      needs a review sign-off bound to the plugin's source digest;
//   ALPHA_TESTED  adds alpha evidence bound to the binary's SHA-256;
//   INTEGRATED    adds integration evidence bound to the same binary;
//   VALIDATED     adds a promotion sign-off bound to the source digest.
// So a rebuilt binary falls back to REVIEWED (its sign-offs still hold) and must re-run the
// automated stages; a source change falls back to UNVALIDATED. A promotion survives a rebuild
// of the same source: once the automated stages pass again the plugin is VALIDATED again,
// which is how committed sign-offs validate the shipped plugins on a fresh build.
//
// Errors: every refused operation returns InvalidInput with one line naming the plugin and
// the rule; file problems return Io (or InvalidInput for a malformed file) naming the file and
// the field. Nothing is ever thrown.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/result.hpp"
#include "core/sha256.hpp"  // file_sha256, which callers of the registry use with it

namespace acetate {

enum class ValidationStage { Unvalidated, Reviewed, AlphaTested, Integrated, Validated };

// "UNVALIDATED", "REVIEWED", "ALPHA_TESTED", "INTEGRATED", "VALIDATED": the file's and the
// messages' spelling.
const char* to_string(ValidationStage stage);
// The names above in any case, '-' accepted for '_' (so the CLI's "alpha-tested" parses).
std::optional<ValidationStage> parse_validation_stage(std::string_view name);

// A maintainer's sign-off: a review (-> REVIEWED) or a promotion (-> VALIDATED).
struct SignOff {
    std::string by;             // who; never empty
    std::string at;             // when, ISO-8601 UTC: 2025-11-22T08:51:00Z
    std::string notes;          // free text, may be empty
    std::string source_digest;  // the source it vouches for
    // The maintainer's SSH signature of sign_off_statement() (armored, as `ssh-keygen -Y sign`
    // writes it); empty when unsigned. Only a signature that verifies against the allowed
    // signers makes the sign-off count (Registry::verify_sign_offs).
    std::string signature;
    bool operator==(const SignOff&) const = default;
};

// A maintainer's acceptance of one check failing for one plugin source, for a stated reason and
// until a stated day (docs/registry.md, "Waivers"). A waived check reads WAIVED, never PASS; an
// expired waiver fails validation and blocks promotion.
struct Waiver {
    std::string check;          // a harness check, or "strictness" (evidence below the default)
    std::string reason;         // why; never empty
    std::string by, at;         // who; when, ISO-8601 UTC
    std::string until;          // the last day it holds, YYYY-MM-DD (UTC)
    std::string source_digest;  // the source it was granted for
    // Whether `today` (YYYY-MM-DD) is past the last day.
    bool expired(std::string_view today) const { return today > std::string_view(until); }
    bool operator==(const Waiver&) const = default;
};
// The harness's default strictness: evidence taken below it is promoted only under a waiver of
// the check "strictness" (kStrictnessWaiver).
inline constexpr int kDefaultStrictness = 5;
inline constexpr const char* kStrictnessWaiver = "strictness";

// The evidence of one passing automated stage run (ALPHA_TESTED or INTEGRATED).
struct StageEvidence {
    std::string at;                          // ISO-8601 UTC; left empty, recording fills in now
    std::string harness_version;             // never empty
    std::string summary;                     // one line for people
    std::map<std::string, uint64_t> counts;  // verdict -> cases: PASS, WARN, SKIP, ...
    std::string report;                      // where the run's report is; may be empty
    std::string binary_sha256;               // what it ran on; set by record_evidence
    int strictness = 0;            // the run's --strictness; 0: not recorded (an older harness)
    std::optional<uint64_t> seed;  // the run's --seed; none: not recorded (an older harness)
    bool operator==(const StageEvidence&) const = default;
};

// One plugin version: the binary and source it was last recorded with, and the records.
struct RegistryEntry {
    std::string id;       // reverse-DNS, as in the descriptor
    std::string version;  // "MAJOR.MINOR.PATCH"
    std::string binary_sha256, source_digest;
    std::optional<SignOff> review, promotion;
    std::optional<StageEvidence> alpha_tested, integrated;
    std::vector<Waiver> waivers;  // for source_digest, one per check, sorted by check
    // Filled by Registry::verify_sign_offs, never stored: for "review" and "promotion", why
    // that sign-off was dropped (its signature is missing, wrong, or made by a key not allowed).
    std::map<std::string, std::string> distrusted;
    // Filled by Registry::verify_sign_offs, never stored: the review was signed by the
    // plugin's own author (a principal the author scopes list for this id; ssh_signature.hpp).
    bool review_by_author = false;

    // The highest stage whose records (and all earlier ones) bind to this binary and source.
    ValidationStage stage_for(std::string_view binary_sha256, std::string_view source_digest) const;
    // The same for the binary and source recorded in the entry.
    ValidationStage stage() const { return stage_for(binary_sha256, source_digest); }
    bool operator==(const RegistryEntry&) const = default;
};

// What a maintainer's signature covers, the bytes `ssh-keygen -Y sign` signs: one line of JSON
// with the format ("acetate-signoff/1"), the plugin id and version, the stage the sign-off
// grants (REVIEWED or VALIDATED), and the sign-off's source digest, maintainer, time and notes.
std::string sign_off_statement(std::string_view id, std::string_view version, ValidationStage stage,
                               const SignOff& sign_off);

class SignatureVerifier;

// Selects the entry of one plugin id and version (for Registry::verify_sign_offs).
std::function<bool(const RegistryEntry&)> entry_of(std::string_view id, std::string_view version);

class Registry {
  public:
    static constexpr std::string_view kFormat = "acetate-registry/1";
    // Returns "now" for new records; tests replace it to get fixed times.
    using Clock = std::function<std::string()>;

    Registry();

    // Parses `json_text`; errors start with `name` and give the field path, e.g.
    // `registry.json: plugins[2].review.at: "yesterday" is not ISO-8601 UTC`.
    static Result<Registry> parse(std::string_view json_text, std::string_view name);
    // Only the entries whose text `wanted` selects, each read strictly (registry_scan.hpp):
    // what a host needs from a registry of thousands. A file that is not well-formed, or not
    // in this format, is read whole as parse() reads it (and so refused the same way); a
    // malformed entry the selection skips goes unnoticed here (`status` reads every entry).
    static Result<Registry> parse_selected(std::string_view json_text, std::string_view name,
                                           const std::function<bool(std::string_view)>& wanted);
    // Reads `file`. A missing file is an empty registry (nothing validated yet); Io when it
    // exists but cannot be read; InvalidInput when malformed. Needs no lock: writers replace the
    // file atomically, so a reader sees one complete version.
    static Result<Registry> load(const std::filesystem::path& file);
    // The file's bytes: entries sorted by id, then version; the same registry gives the same
    // bytes (the file is meant to be committed and diffed).
    std::string to_json() const;
    // Writes `file` atomically (temp sibling, fsync, rename). Concurrent writers must use
    // update(), which holds the lock.
    Result<void> save(const std::filesystem::path& file) const;

    // Read-modify-write under an exclusive flock on `<file>.lock`: loads `file`, runs `change`,
    // and if it succeeds writes `file` atomically (and `markdown`, when not empty, rendered
    // from the result). If `change` fails nothing is written and its error is returned. Holds
    // the lock only for this call, so `change` must be quick (record results, don't run checks)
    // and must not fork a child that lives on without exec'ing: the lock's descriptor is
    // close-on-exec, so a tool started with posix_spawn (validate's import checks signatures
    // with ssh-keygen here) does not hold it. Under the lock, temporaries left by a killed
    // writer are removed.
    static Result<void> update(const std::filesystem::path& file,
                               const std::function<Result<void>(Registry&)>& change,
                               const std::filesystem::path& markdown = {});

    // Sorted by id, then version (numerically).
    const std::vector<RegistryEntry>& entries() const { return entries_; }
    const RegistryEntry* find(std::string_view id, std::string_view version) const;

    // Records a review of the plugin built from `source_digest` as `binary_sha256`: REVIEWED
    // (or the stage it had, when re-reviewing the same source). Refused when `reviewer` is
    // empty or an argument is malformed. A new binary or source replaces the entry's; records
    // bound to the old ones are dropped.
    Result<void> record_review(std::string_view id, std::string_view version,
                               std::string_view binary_sha256, std::string_view source_digest,
                               std::string_view reviewer, std::string_view notes);
    // The same with a complete sign-off, as `acetate-harness review` signs it: its time and
    // signature are kept; refused when its source digest is not `source_digest`.
    Result<void> record_review(std::string_view id, std::string_view version,
                               std::string_view binary_sha256, std::string_view source_digest,
                               SignOff review);
    // Records a passing run of `stage` (AlphaTested or Integrated) on `binary_sha256`. Refused
    // unless the plugin holds the stage before it for this binary and source (the message
    // names the missing stage), or when `evidence` counts any FAIL, CRASH or TIMEOUT.
    // Re-recording a stage already held replaces its evidence.
    Result<void> record_evidence(std::string_view id, std::string_view version,
                                 std::string_view binary_sha256, std::string_view source_digest,
                                 ValidationStage stage, StageEvidence evidence);
    // Records a waiver for the plugin's source (replacing one of the same check). Refused
    // unless the plugin is at least REVIEWED for this binary and source, or when the check,
    // the reason or the name is empty, or `until` is not a YYYY-MM-DD day from today on.
    Result<void> waive(std::string_view id, std::string_view version,
                       std::string_view binary_sha256, std::string_view source_digest,
                       Waiver waiver);
    // INTEGRATED -> VALIDATED for the entry's recorded binary and source; refused from any
    // other stage, or when `by` is empty, or while a waiver has expired, or when evidence was
    // taken below kDefaultStrictness and no waiver of "strictness" says why.
    Result<void> promote(std::string_view id, std::string_view version, std::string_view by,
                         std::string_view notes);
    // The same with a complete sign-off, as `acetate-harness promote` signs it; a promotion
    // already recorded is replaced (whoever calls this found it untrusted).
    Result<void> promote(std::string_view id, std::string_view version, SignOff promotion);

    // Checks the signature of every sign-off in the entries `which` selects (every entry when
    // empty) against `verifier`. A sign-off whose signature is missing, does not match its
    // statement, or was made by a key the allowed signers do not list for its maintainer (or a
    // revoked key) is dropped from this copy, and the entry's `distrusted` says why; its stage
    // falls accordingly, and explain() and require_validated() give that reason. Whoever trusts
    // a stage (the host, validate, status, promote) loads the registry, then calls this: writing
    // the file is not enough to validate a plugin. Runs ssh-keygen once per sign-off.
    void verify_sign_offs(const SignatureVerifier& verifier,
                          const std::function<bool(const RegistryEntry&)>& which = {});

    // The stage this exact binary and source hold (UNVALIDATED when the plugin is unknown).
    ValidationStage effective_stage(std::string_view id, std::string_view version,
                                    std::string_view binary_sha256,
                                    std::string_view source_digest) const;
    // Host policy: some version of `id` is VALIDATED for exactly this binary.
    bool is_validated(std::string_view id, std::string_view binary_sha256) const;
    // Host policy with a reason: ok when VALIDATED, else InvalidInput naming the plugin, its
    // stage and the first missing record, e.g. `org.acetate.bloom 1.0.0: is REVIEWED, not
    // VALIDATED: no ALPHA_TESTED evidence for binary 3f2a9c1e0b7d (recorded for 9e1b44a0c2d1)`.
    Result<void> require_validated(std::string_view id, std::string_view version,
                                   std::string_view binary_sha256,
                                   std::string_view source_digest) const;

    // Host policy before loading: the host knows the file's SHA-256 but not yet its version or
    // source digest (reading the descriptor means loading it). The highest stage any version
    // of `id` holds for exactly this binary (UNVALIDATED when none was recorded with it);
    // an empty `id` matches every plugin (for a file loaded by path, judged by its bytes
    // alone). binary_stage(id, sha) == VALIDATED exactly when is_validated(id, sha).
    ValidationStage binary_stage(std::string_view id, std::string_view binary_sha256) const;
    // Why, in one line: the stage this binary holds and the first record it lacks, or what the
    // registry has instead. E.g.
    //   `org.acetate.bloom 1.2.0 is REVIEWED for this binary: no ALPHA_TESTED evidence for
    //   binary 5be01c77a4d2`,
    //   `org.acetate.bloom is UNVALIDATED for this binary: recorded only for other binaries:
    //   1.2.0 VALIDATED for 3f2a9c1e0b7d`,
    //   `org.acetate.bloom is UNVALIDATED: no record of it`,
    //   `org.acetate.bloom 1.2.0 is VALIDATED for this binary`.
    std::string explain(std::string_view id, std::string_view binary_sha256) const;

    void set_clock(Clock clock) { clock_ = std::move(clock); }

  private:
    RegistryEntry& entry_for(std::string_view id, std::string_view version);

    std::vector<RegistryEntry> entries_;
    Clock clock_;
};

// VALIDATION-REGISTRY.md: a table (plugin, version, stage, short hashes, who/when of each
// sign-off and evidence), then each plugin's notes, summaries and report paths. `source_name`
// is the JSON file it says it was generated from.
std::string render_registry_markdown(const Registry& registry, std::string_view source_name);
// Renders and writes `file` atomically.
Result<void> write_registry_markdown(const Registry& registry, const std::filesystem::path& file,
                                     std::string_view source_name);

// The current time as ISO-8601 UTC, whole seconds: 2025-11-22T08:51:00Z.
std::string utc_now_iso8601();

}  // namespace acetate
