#pragma once
// What `acetate-harness validate` reads from and writes to the registry: the stage a plugin
// holds (its sign-offs verified against the allowed signers, as a host checks them), the
// committed sign-offs it imports, the evidence it records, the history its report shows.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "case_spec.hpp"
#include "core/result.hpp"
#include "registry.hpp"
#include "report.hpp"
#include "ssh_signature.hpp"
#include "validate.hpp"

namespace acetate::harness {

// The registry as one run sees it: read once when the run starts, changed in memory as sign-offs
// are imported and stages pass, and written in one locked update when the run ends without
// being refused (commit). A refused run (a merge missing a case, a result not in the plan, a
// registry that cannot be read) never commits, so it leaves the registry as it found it.
class RegistryTransaction {
  public:
    // An error when the file exists but cannot be read or parsed.
    static Result<RegistryTransaction> open(std::filesystem::path file);

    // What the run has read and changed so far.
    const Registry& view() const { return view_; }
    // Applies `change` to the view now and keeps it for commit(); an error changes nothing.
    Result<void> apply(std::function<Result<void>(Registry&)> change);
    // Writes every kept change, in order, onto the registry as it is on disk then (under its
    // lock, so another run's records made meanwhile are kept). Writes nothing when no change
    // was kept.
    Result<void> commit() const;

  private:
    std::filesystem::path file_;
    Registry view_;
    std::vector<std::function<Result<void>(Registry&)>> changes_;
};

// The stage this binary and source hold in `registry`, counting only sign-offs whose
// signatures hold.
ValidationStage current_stage(const Registry& registry, const ValidateOptions& o,
                              const PluginInfo& plugin);

// Records a passing run of `stage` as evidence bound to the plugin's binary (in `registry`,
// written when it commits).
Result<void> record(RegistryTransaction& registry, const ValidateOptions& o,
                    const PluginInfo& plugin, ValidationStage stage,
                    const std::vector<CaseResult>& results, const std::string& report,
                    const std::vector<CompanionPlugin>& companions);

// Imports the committed sign-offs (--signoffs) whose signatures hold; returns what was
// imported, and a line for each committed sign-off left out because its signature does not.
Result<std::vector<std::string>> import_committed(RegistryTransaction& registry,
                                                  const ValidateOptions& o,
                                                  const PluginInfo& plugin);

// Copies into `registry` the sign-offs `signoffs` holds for this plugin's id, version and
// source digest where the registry's own (verified with `verifier`) do not reach as far: a
// review when none holds, a promotion once the plugin is INTEGRATED (a promotion cannot skip
// stages). `signoffs` must already be verified. Returns what was imported, for the log.
std::vector<std::string> import_signoffs(Registry& registry, const Registry& signoffs,
                                         const PluginInfo& plugin,
                                         const SignatureVerifier& verifier);

// Every record the registry holds for the plugin, oldest first, for the report.
std::vector<HistoryLine> history_of(const Registry& registry, const PluginInfo& plugin);

}  // namespace acetate::harness
