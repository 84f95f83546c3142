#pragma once
// acetate-bench's runner: for each scene and plugin, every preset in every target format,
// timed and compared with the reference configuration (the plugin at `ultra` with rgba32f
// targets), then the same flattening by another tool (peer_flatten.hpp).

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_results.hpp"
#include "core/result.hpp"
#include "render/renderer.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::bench {

struct BenchOptions {
    std::vector<std::filesystem::path> scenes;
    std::vector<std::string> plugins;  // empty: every plugin each scene names
    // Empty: every preset each plugin declares, in its order.
    std::vector<std::string> presets;
    std::vector<std::string> formats{"rgba16f", "rgba32f"};
    uint32_t frames = 15;           // timed frames per configuration, after the first
    double time = 2.5;              // seconds: the animation time every frame shows
    std::optional<uint32_t> floor;  // the active floor; the scene's own when unset
    std::vector<std::filesystem::path> plugin_paths;
    ErrorThresholds thresholds;
    std::optional<std::filesystem::path> heat_map_dir;  // heat-map PNGs go here when set
    bool peers = true;  // time oiiotool's flattening of each scene beside acetate's
};

// The device and the renderer every measurement of a run shares (the pipeline pool and the
// loaded plugins live as long as it does).
struct BenchDevice {
    std::unique_ptr<VulkanContext> context;
    std::unique_ptr<Renderer> renderer;
    // An error naming the first Vulkan validation message, if any was printed (with
    // ACETATE_VALIDATION=1 the bench fails on one, like the test suite).
    Result<void> check_validation() const;
};
// ACETATE_DEVICE picks the device, ACETATE_VALIDATION=1 turns the layers on.
Result<BenchDevice> open_device(const std::vector<std::filesystem::path>& plugin_paths);

// One line per configuration as it starts ("[3/18] harbour.json acetate.water high rgba16f").
using ProgressFn = std::function<void(const std::string& line)>;

// Plugins are loaded without the registry's policy: the bench measures and ships no frame (it
// says so on the progress line). Errors are one line naming the scene, plugin or option.
Result<BenchResults> run_bench(const BenchOptions& options, const ProgressFn& progress);

}  // namespace acetate::bench
