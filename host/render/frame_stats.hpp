#pragma once
// What a load and each frame did, in numbers a test or a person can check (the embedding API
// hands them on as FrameStatistics and LoadStatistics; `acetate render --stats` writes them).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/pixel_rect.hpp"
#include "vulkan/pass_timing.hpp"

namespace acetate {

struct FloorFrameReport {
    uint32_t floor = 0;
    std::string path;  // skipped / direct / through-target
    std::string why;
    PixelRect scissor;
    uint32_t passes = 0;
    uint64_t pixels_shaded = 0;  // sum over this floor's passes of the area they shade
    uint64_t violations = 0;     // see FrameStats::violations
};

struct FrameStats {
    uint32_t active_floor = 0;
    double milliseconds = 0;         // record + submit + wait for the frame
    uint32_t passes = 0;             // draws recorded
    uint64_t pixels_shaded = 0;      // sum over passes of their scissored area
    uint64_t images_loaded = 0;      // during this frame (a warm frame: 0)
    uint64_t targets_allocated = 0;  // during this frame
    uint64_t shaders_compiled = 0;   // during this frame
    uint64_t pipelines_created = 0;  // during this frame
    uint64_t barriers = 0;           // pipeline barriers recorded (ResourceCounters)
    // The compiled frame's passes that ran (host and effect passes, clears included: each is at
    // most one barrier command), and those culled because nothing read what they write.
    uint32_t frame_passes = 0;
    uint32_t frame_passes_culled = 0;
    // Pixels of floor content reaching the composite with a == 0 but rgb != 0, or NaN/Inf,
    // counted on the GPU. A floor drawn directly has only its tiles as content, and tile texels
    // are checked once at load (LoadStats::tile_texel_violations).
    uint64_t violations = 0;
    std::vector<FloorFrameReport> floors;
    std::optional<FloorFrameReport> global;  // the global effects, when the scene has any
    std::vector<PassTiming> gpu_passes;      // only with CompositorOptions::gpu_timings
};

struct LoadStats {
    double milliseconds = 0;
    uint64_t images_loaded = 0;
    uint64_t targets_allocated = 0;
    uint64_t shaders_compiled = 0;
    uint64_t pipelines_created = 0;
    uint64_t tile_texel_violations = 0;  // texels with colour at alpha 0 (dropped when drawn)
};

struct TargetInfo {
    std::string name;
    std::string format;
    uint32_t width = 0, height = 0;
    uint64_t bytes = 0;
};

}  // namespace acetate
