#pragma once
// What the output image shows: the picture, or a debug view (docs/design.md, L-debug-views).
// The output pass (output.frag) reads the view as a push constant with these values.

#include <array>
#include <cstdint>
#include <string>

#include "core/result.hpp"

namespace acetate {

enum class OutputView {
    Normal = 0,      // the composite over the canvas background
    FloorAlpha = 1,  // the active floor's own alpha, grey
    AccumAlpha = 2,  // the accumulation's alpha, grey
    FloorRgb = 3,    // the active floor's rgb with alpha forced to 1
    Violations = 4,  // red where the active floor has a <= 0 but rgb != 0 (or NaN/Inf)
    Isolation = 5,   // each floor tinted its own colour
};
// "normal", "floor-alpha", ...; anything else is InvalidInput listing the choices.
Result<OutputView> parse_view(const std::string& name);
const char* to_string(OutputView view);
// Views that read the active floor's own target (which then must exist).
bool view_reads_floor_target(OutputView view);
// The isolation tint of floor `index` (linear rgb, distinct for neighbouring floors).
std::array<float, 3> isolation_tint(uint32_t index);

}  // namespace acetate
