#pragma once
// Outputs never destroy inputs: before any work, a program lists every file the run reads and
// every file it will write, and refuses (one line, exit 1) an output that is one of the inputs
// (the same file, also through another name, a symbolic or a hard link) or that two outputs
// share. Used by `acetate render`, `acetate-harness` (validate, merge, bless, fuzz) and
// `acetate-bench` (docs/conventions.md, "outputs never destroy inputs").

#include <filesystem>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace acetate {

struct RunFile {
    std::filesystem::path path;
    // How a message names it: "-o", "--stats", "scene.json: floors[0].tiles[1].image".
    std::string role;
};

// An error naming the output and the input (or the other output) it would overwrite.
Result<void> check_outputs_spare_inputs(const std::vector<RunFile>& outputs,
                                        const std::vector<RunFile>& inputs);

}  // namespace acetate
