#include "render/frame_plan.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace acetate {

const char* to_string(FloorPath path) {
    switch (path) {
        case FloorPath::Skipped:
            return "skipped";
        case FloorPath::Direct:
            return "direct";
        case FloorPath::ThroughTarget:
            return "through-target";
    }
    return "?";
}

FramePlan plan_frame(uint32_t width, uint32_t height, const std::vector<FloorGeometry>& floors,
                     uint32_t active_floor, const PlanOptions& options) {
    assert(active_floor < floors.size());
    const PixelRect canvas{0, 0, int64_t(width), int64_t(height)};
    FramePlan plan;
    std::vector<PixelRect> opaque_above;  // opaque tiles of the floors above the one planned
    plan.steps.resize(active_floor + 1);
    for (int64_t f = active_floor; f >= 0; --f) {
        const FloorGeometry& floor = floors[size_t(f)];
        FloorStep& step = plan.steps[size_t(f)];
        step.floor = uint32_t(f);
        step.scissor = options.scissor_to_coverage ? floor.coverage : canvas;
        if (floor.coverage.empty()) {
            step.path = FloorPath::Skipped;
            step.why = "covers no pixel of the canvas";
        } else if (options.cull_hidden_floors && f != options.force_target_floor &&
                   covered_by_union(floor.coverage, opaque_above)) {
            // Over with an opaque source ignores the destination: nothing of this floor shows.
            step.path = FloorPath::Skipped;
            step.why = "hidden under opaque floors above";
        } else if (floor.needs_target || !options.draw_direct || f == options.force_target_floor) {
            step.path = FloorPath::ThroughTarget;
            step.why = floor.needs_target ? "has effects" : "its own target was requested";
        } else {
            step.path = FloorPath::Direct;
            step.why = "no effects: tiles go straight into the accumulation";
        }
        opaque_above.insert(opaque_above.end(), floor.opaque.begin(), floor.opaque.end());
    }
    return plan;
}

}  // namespace acetate
