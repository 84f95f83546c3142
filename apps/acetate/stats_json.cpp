#include "stats_json.hpp"

namespace acetate {
namespace {

nlohmann::json step_json(const host::StepStatistics& s) {
    return {{"floor", s.floor},
            {"path", s.path},
            {"why", s.why},
            {"scissor", {s.x, s.y, s.width, s.height}},
            {"passes", s.passes},
            {"pixels_shaded", s.pixels_shaded},
            {"violations", s.violations}};
}

}  // namespace

nlohmann::json to_json(const host::FrameStatistics& frame) {
    nlohmann::json floors = nlohmann::json::array();
    for (const host::StepStatistics& f : frame.floors) floors.push_back(step_json(f));
    nlohmann::json out = {{"active_floor", frame.active_floor},
                          {"milliseconds", frame.milliseconds},
                          {"passes", frame.passes},
                          {"pixels_shaded", frame.pixels_shaded},
                          {"images_loaded", frame.images_loaded},
                          {"render_targets_allocated", frame.targets_allocated},
                          {"shaders_compiled", frame.shaders_compiled},
                          {"pipelines_created", frame.pipelines_created},
                          {"barriers", frame.barriers},
                          {"premultiplied_violations", frame.violations},
                          {"floors", floors}};
    if (frame.global_effects) out["global_effects"] = step_json(*frame.global_effects);
    return out;
}

nlohmann::json to_json(const host::LoadStatistics& load) {
    return {{"milliseconds", load.milliseconds},
            {"images_loaded", load.images_loaded},
            {"render_targets_allocated", load.targets_allocated},
            {"shaders_compiled", load.shaders_compiled},
            {"pipelines_created", load.pipelines_created},
            {"tile_texel_violations", load.tile_texel_violations}};
}

nlohmann::json to_json(const host::ImageInfo& image) {
    return {{"name", image.name},
            {"format", image.format},
            {"width", image.width},
            {"height", image.height},
            {"bytes", image.bytes}};
}

}  // namespace acetate
