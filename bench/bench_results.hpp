#pragma once
// What acetate-bench measures, as plain data: the runner fills it, the JSON and HTML reports
// print it. Times are milliseconds of wall clock (record + submit + wait, as FrameStats) or of
// GPU time between Vulkan timestamps; errors are against the reference configuration (the
// plugin at its `ultra` preset with rgba32f targets), over premultiplied linear RGBA.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "image_compare.hpp"

namespace acetate::bench {

// GPU time of one recorded step of the frame (a host pass or one effect pass), median over the
// timed frames.
struct PassTime {
    std::string name;  // e.g. "floor 0 tiles", "floor 0 acetate.water:shade", "output"
    double milliseconds = 0;
};

// One plugin at one preset in one target format, on one scene.
struct ConfigResult {
    std::string scene;   // the scene file as given
    std::string plugin;  // the plugin whose instances took `preset`
    std::string preset;  // low / medium / high / ultra, or "off" (its instances removed)
    std::string format;  // rgba16f / rgba32f
    bool reference = false;
    uint32_t floor = 0;  // the active floor rendered
    uint32_t frames = 0;
    double median_ms = 0, min_ms = 0, max_ms = 0;  // steady frames, after the first
    double first_frame_ms = 0;                     // the first frame after load
    double load_ms = 0;
    std::vector<PassTime> gpu_passes;  // empty when the device has no timestamps
    double gpu_total_ms = 0;           // sum of gpu_passes
    // GPU time of `plugin`'s own passes (its instances on every floor): the effect's cost
    // without the rest of the frame's noise. 0 for "off" and without timestamps.
    double effect_gpu_ms = 0;
    uint64_t pixels_shaded = 0;
    ErrorStats error;
    std::string heat_map;  // PNG file name, relative to the HTML folder; empty if none written
};

// The same flattening done by another tool, timed in the same run.
struct PeerComparison {
    std::string scene;
    std::string tool;     // "oiiotool --over"
    std::string command;  // what was run, for the reader to repeat
    double tool_ms = 0;   // the tool's whole run (median of its runs), files read and written
    // Its --over operations alone: the same ImageBufAlgo::over chain in the bench's process,
    // on tiles decoded beforehand (oiiotool --runstats rounds to 10 ms).
    double tool_over_ms = 0;
    double acetate_frame_ms = 0;  // a steady frame of the same scene with no effects
    // Load (tiles decoded, uploaded), first frame, read back and EXR written, in one process:
    // what the tool's run does, less the process start and the device creation.
    double acetate_run_ms = 0;
    ErrorStats difference;  // the tool's image against acetate's
    std::string note;       // why one wins, in one line
};

// The frame against its limits, per scene as given (its own presets, rgba16f targets), measured
// before anything else runs in the process, so the first frame meets only what the scene's
// own load compiled.
struct FrameLimits {
    std::string scene;
    uint32_t floor = 0;             // the active floor
    double steady_ms = 0;           // median of the timed frames there
    double first_frame_ms = 0;      // the first frame after the scene's load
    int64_t switch_floor = -1;      // the floor switched to; -1 when the scene has one floor
    double switch_ms = 0;           // the first frame after switching to it
    double switch_steady_ms = 0;    // steady frames at that floor
    uint64_t pixels_shaded = 0;     // a frame at `floor` (FrameStats::pixels_shaded)
    uint64_t necessary_pixels = 0;  // the fewest any renderer must shade there
};

struct BenchResults {
    std::string device;
    std::string date;  // UTC, ISO 8601
    std::string load;  // /proc/loadavg at the start: the machine is shared
    uint32_t frames = 0;
    ErrorThresholds thresholds;
    std::vector<ConfigResult> configs;
    std::vector<PeerComparison> peers;
    std::vector<FrameLimits> limits;
};

}  // namespace acetate::bench
