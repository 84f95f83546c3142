#pragma once
// The harness's neighbour effect (harness/neighbours/spread.cpp), which the context cases place
// before and after the plugin under test: where its files are, and the companions a case's
// child loads for them, each with the SHA-256 the parent read (the child loads only
// those bytes, as it does for an integration case's companions).

#include <filesystem>
#include <string>
#include <vector>

#include "case_spec.hpp"
#include "core/result.hpp"

namespace acetate::harness {

// "acetate.harness.spread_floor" or "acetate.harness.spread_global": the neighbour for a plugin
// of that scope (a floor effect's neighbours are floor effects).
std::string spread_neighbour_id(bool global);

// The folder holding the neighbours: beside the program in the build tree
// (<build>/harness/neighbours), or <prefix>/<libdir>/acetate/harness-neighbours when installed.
std::filesystem::path neighbour_directory(const std::filesystem::path& harness_program);

// Adds to each case that places neighbours (effects_before, effects_after) one companion per
// neighbour: its file under `directory` and that file's SHA-256. Fails, naming the file, when
// one is missing or unreadable.
Result<void> attach_neighbours(std::vector<CaseSpec>& cases,
                               const std::filesystem::path& directory);

}  // namespace acetate::harness
