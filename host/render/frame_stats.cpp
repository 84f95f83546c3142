#include "render/frame_stats.hpp"

namespace acetate {

namespace {
nlohmann::json report_json(const FloorFrameReport& f) {
    return {
        {"floor", f.floor},
        {"path", f.path},
        {"why", f.why},
        {"scissor",
         {f.scissor.x0, f.scissor.y0, f.scissor.x1 - f.scissor.x0, f.scissor.y1 - f.scissor.y0}},
        {"passes", f.passes},
        {"pixels_shaded", f.pixels_shaded},
        {"violations", f.violations}};
}
}  // namespace

nlohmann::json to_json(const FrameStats& s) {
    nlohmann::json floors = nlohmann::json::array();
    for (const FloorFrameReport& f : s.floors) floors.push_back(report_json(f));
    nlohmann::json out = {{"active_floor", s.active_floor},
                          {"milliseconds", s.milliseconds},
                          {"passes", s.passes},
                          {"pixels_shaded", s.pixels_shaded},
                          {"images_loaded", s.images_loaded},
                          {"render_targets_allocated", s.targets_allocated},
                          {"shaders_compiled", s.shaders_compiled},
                          {"pipelines_created", s.pipelines_created},
                          {"premultiplied_violations", s.violations},
                          {"floors", floors}};
    if (s.global) out["global_effects"] = report_json(*s.global);
    if (!s.gpu_passes.empty()) {
        nlohmann::json passes = nlohmann::json::array();
        for (const PassTiming& p : s.gpu_passes)
            passes.push_back({{"name", p.name}, {"gpu_milliseconds", p.milliseconds}});
        out["gpu_passes"] = passes;
    }
    return out;
}

nlohmann::json to_json(const LoadStats& s) {
    return {{"milliseconds", s.milliseconds},
            {"images_loaded", s.images_loaded},
            {"render_targets_allocated", s.targets_allocated},
            {"shaders_compiled", s.shaders_compiled},
            {"pipelines_created", s.pipelines_created},
            {"tile_texel_violations", s.tile_texel_violations}};
}

nlohmann::json to_json(const TargetInfo& t) {
    return {{"name", t.name},
            {"format", t.format},
            {"width", t.width},
            {"height", t.height},
            {"bytes", t.bytes}};
}

}  // namespace acetate
