#pragma once
// What `acetate-harness validate` reads from and writes to the registry: the stage a plugin
// holds (its sign-offs verified against the allowed signers, as a host checks them), the
// committed sign-offs it imports, the evidence it records, the history its report shows.

#include <string>
#include <vector>

#include "case_spec.hpp"
#include "core/result.hpp"
#include "registry.hpp"
#include "report.hpp"
#include "ssh_signature.hpp"
#include "validate.hpp"

namespace acetate::harness {

// The stage this binary and source hold, counting only sign-offs whose signatures hold.
ValidationStage current_stage(const ValidateOptions& o, const PluginInfo& plugin);

// Records a passing run of `stage` as evidence bound to the plugin's binary.
Result<void> record(const ValidateOptions& o, const PluginInfo& plugin, ValidationStage stage,
                    const std::vector<CaseResult>& results, const std::string& report,
                    const std::vector<CompanionPlugin>& companions);

// Imports the committed sign-offs (--signoffs) whose signatures hold; returns what was
// imported, and a line for each committed sign-off left out because its signature does not.
Result<std::vector<std::string>> import_committed(const ValidateOptions& o,
                                                  const PluginInfo& plugin);

// Copies into `registry` the sign-offs `signoffs` holds for this plugin's id, version and
// source digest where the registry's own (verified with `verifier`) do not reach as far: a
// review when none holds, a promotion once the plugin is INTEGRATED (a promotion cannot skip
// stages). `signoffs` must already be verified. Returns what was imported, for the log.
std::vector<std::string> import_signoffs(Registry& registry, const Registry& signoffs,
                                         const PluginInfo& plugin,
                                         const SignatureVerifier& verifier);

// Every record the registry holds for the plugin, oldest first, for the report.
std::vector<HistoryLine> history_of(const ValidateOptions& o, const PluginInfo& plugin);

}  // namespace acetate::harness
