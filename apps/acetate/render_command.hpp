#pragma once
// `acetate render`: load one scene, render a sequence of active floors, write images and stats.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "param_flags.hpp"

namespace acetate {

struct RenderCommand {
    std::vector<std::filesystem::path> scenes;        // rendered in turn in one process
    std::filesystem::path output;                     // .exr or .png
    std::optional<uint32_t> floor;                    // --floor N
    std::vector<uint32_t> floors;                     // --floors 0,1,2,1
    bool all_floors = false;                          // --floors all: 0..n-1 of each scene
    std::string view = "normal";                      // --view
    std::string format = "rgba16f";                   // --format
    std::optional<std::filesystem::path> stats;       // --stats FILE
    std::vector<std::filesystem::path> plugin_paths;  // --plugin-path DIR (repeatable)
    double time = 0;  // --time SECONDS: what effects animate with (double: smooth at 10^5 s)
    // --times LIST|START:END:STEP: render each floor at each of these instead, in one process
    // (time_list.hpp); writes OUT with the time's index before the extension.
    std::vector<double> times;
    // --param FLOOR.EFFECT.NAME=VALUE and --preset FLOOR.EFFECT=PRESET (param_flags.hpp): set on
    // every scene after it loads, as if its file said so.
    std::vector<ParamFlag> params;
    bool pipeline_cache = true;  // --no-pipeline-cache turns the disk cache off
    // Host load policy (docs/registry.md, "Host policy"): a plugin is loaded only if the
    // registry has it VALIDATED for its exact binary.
    std::optional<std::filesystem::path> registry;  // --registry FILE, else ACETATE_REGISTRY
    // --allowed-signers FILE, else ACETATE_ALLOWED_SIGNERS, else validation/allowed_signers:
    // the maintainers' keys; a sign-off whose signature they do not verify does not count.
    std::optional<std::filesystem::path> allowed_signers;
    bool allow_unvalidated = false;  // --allow-unvalidated: load with a warning
};

// Runs the command; prints progress to stdout and one-line errors to stderr. Returns the exit
// status: 0 on success, 1 on bad input or a failure of the environment (usage errors caught
// by the argument parser exit 2, in main.cpp).
int run_render(const RenderCommand& command);

// The file a frame of floor `floor` goes to: OUT itself for a single frame, else OUT with the
// floor index before the extension (`out.floor1.png`).
std::filesystem::path frame_output_path(const std::filesystem::path& output, uint32_t floor,
                                        bool several);
// With several scenes, `.sceneK` goes before the floor part (`out.scene2.floor1.png`).
std::filesystem::path scene_output_path(const std::filesystem::path& output, size_t scene,
                                        bool several);
// With several times, `.frameNNNN` (the time's index in --times, four digits or more) goes
// after the floor part (`out.floor1.frame0003.png`).
std::filesystem::path time_output_path(const std::filesystem::path& output, size_t index,
                                       bool several);

}  // namespace acetate
