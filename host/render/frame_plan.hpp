#pragma once
// Decides, on the CPU and before anything is recorded, what a frame does for each floor:
// skip it, draw its tiles straight into the accumulation, or render it through its own floor
// target. Pure logic, testable without a GPU.

#include <cstdint>
#include <string>
#include <vector>

#include "core/pixel_rect.hpp"

namespace acetate {

// What the planner needs to know of one floor, computed once at load.
struct FloorGeometry {
    PixelRect coverage;             // bounds of all its tiles (empty: covers nothing)
    std::vector<PixelRect> opaque;  // pixel rects of its tiles whose alpha is 1 everywhere
    bool needs_target = false;      // it has effects, so it needs a floor target
};

struct PlanOptions {
    bool scissor_to_coverage = true;  // passes shade only the floor's coverage bounds
    bool cull_hidden_floors = true;   // skip floors under opaque coverage of floors above
    bool draw_direct = true;          // floors without effects draw straight into the accum
    bool merge_direct_floors = true;  // consecutive direct floors share one rendering pass
    int64_t force_target_floor = -1;  // this floor goes through its target (debug views)
    // The floor's and the composite's working images share memory where a frame uses them at
    // different times (render/frame_targets.hpp).
    bool share_targets = true;
};

enum class FloorPath { Skipped, Direct, ThroughTarget };
const char* to_string(FloorPath path);

struct FloorStep {
    uint32_t floor = 0;
    FloorPath path = FloorPath::Skipped;
    PixelRect scissor;  // the area its passes may shade
    std::string why;    // e.g. "hidden under opaque floors above"
};

struct FramePlan {
    std::vector<FloorStep> steps;  // floors 0..active, bottom to top
};

// Plans floors 0..active_floor of a canvas of width x height.
FramePlan plan_frame(uint32_t width, uint32_t height, const std::vector<FloorGeometry>& floors,
                     uint32_t active_floor, const PlanOptions& options);

}  // namespace acetate
