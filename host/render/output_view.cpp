#include "render/output_view.hpp"

#include <fmt/format.h>

#include <cmath>

namespace acetate {

Result<OutputView> parse_view(const std::string& name) {
    for (int v = 0; v <= int(OutputView::Isolation); ++v)
        if (name == to_string(OutputView(v))) return OutputView(v);
    return make_error(ErrorCode::InvalidInput,
                      fmt::format("unknown view \"{}\"; expected normal, floor-alpha, "
                                  "accum-alpha, floor-rgb, violations or isolation",
                                  name));
}

const char* to_string(OutputView view) {
    switch (view) {
        case OutputView::Normal:
            return "normal";
        case OutputView::FloorAlpha:
            return "floor-alpha";
        case OutputView::AccumAlpha:
            return "accum-alpha";
        case OutputView::FloorRgb:
            return "floor-rgb";
        case OutputView::Violations:
            return "violations";
        case OutputView::Isolation:
            return "isolation";
    }
    return "?";
}

bool view_reads_floor_target(OutputView view) {
    return view == OutputView::FloorAlpha || view == OutputView::FloorRgb ||
           view == OutputView::Violations;
}

std::array<float, 3> isolation_tint(uint32_t index) {
    // Hues spaced by the golden angle so neighbouring floors never look alike.
    const float hue = std::fmod(index * 0.381966f, 1.0f) * 6.0f;
    const float x = 1.0f - std::fabs(std::fmod(hue, 2.0f) - 1.0f);
    const int sector = int(hue);
    const std::array<std::array<float, 3>, 6> rgb = {
        {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}}};
    return rgb[size_t(sector % 6)];
}

}  // namespace acetate
