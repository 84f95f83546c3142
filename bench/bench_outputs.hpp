#pragma once
// The files an acetate-bench run writes, named here for the runner and the program alike, and
// the check that none of them is one of the run's inputs (core/output_paths.hpp): the scenes,
// every tile image and mask they name, and the plugin files the search would load. It runs
// before the device starts, so a refused run has written nothing.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "bench_runner.hpp"
#include "core/result.hpp"

namespace acetate::bench {

// The heat map of one configuration, in the --html folder: heat-s<scene>-<plugin>-<preset>-
// <format>.png, with every character other than a letter, a digit, '.' or '-' made '_'.
std::string heat_map_name(size_t scene, const std::string& plugin, const std::string& preset,
                          const std::string& format);
// The speed-against-error chart of one scene's plugin: speed-error-<scene stem>-<plugin>.svg.
std::string chart_name(const std::filesystem::path& scene, const std::string& plugin);

// An error naming the output and the input it would replace (or the other output it is), if
// --json FILE or any file --html DIR would hold is an input of the run or another output.
Result<void> check_bench_outputs(const BenchOptions& options,
                                 const std::optional<std::filesystem::path>& json,
                                 const std::optional<std::filesystem::path>& html);

}  // namespace acetate::bench
