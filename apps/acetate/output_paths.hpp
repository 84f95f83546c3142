#pragma once
// Outputs never destroy inputs: before anything renders, `acetate render` lists every file the
// run reads and every file it will write, and refuses (one line, exit 1) an output that is one
// of the inputs (the same file, also through another name or a link) or that two outputs share.

#include <filesystem>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace acetate {

struct RunFile {
    std::filesystem::path path;
    std::string
        role;  // how a message names it: "-o", "--stats", "scene.json: floors[0].tiles[1].image"
};

// An error naming the output and the input (or the other output) it would overwrite.
Result<void> check_outputs_spare_inputs(const std::vector<RunFile>& outputs,
                                        const std::vector<RunFile>& inputs);

}  // namespace acetate
