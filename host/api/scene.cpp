// The embedding API's Scene (acetate/host/host.hpp): one Compositor, its active floor and
// time, and its statistics in the API's own types.
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "api/host_internal.hpp"
#include "scene/image_io.hpp"

namespace acetate::host {
namespace {

StepStatistics step_of(const FloorFrameReport& r) {
    return {r.floor,
            r.path,
            r.why,
            r.scissor.x0,
            r.scissor.y0,
            r.scissor.x1 - r.scissor.x0,
            r.scissor.y1 - r.scissor.y0,
            r.passes,
            r.pixels_shaded,
            r.violations};
}

std::vector<ImageInfo> infos_of(const std::vector<TargetInfo>& targets) {
    std::vector<ImageInfo> out;
    for (const TargetInfo& t : targets)
        out.push_back({t.name, t.format, t.width, t.height, t.bytes});
    return out;
}

}  // namespace

Scene::Scene(std::unique_ptr<Loaded> loaded) : loaded_(std::move(loaded)) {}
// The compositor goes first: it uses the renderer and device the Loaded keeps alive.
Scene::~Scene() {
    if (loaded_) loaded_->compositor.reset();
}

uint32_t Scene::width() const {
    return loaded_->desc.width;
}
uint32_t Scene::height() const {
    return loaded_->desc.height;
}
uint32_t Scene::floor_count() const {
    return uint32_t(loaded_->desc.floors.size());
}
std::string Scene::floor_name(uint32_t floor) const {
    return floor < floor_count() ? loaded_->desc.floors[floor].name : std::string();
}
uint32_t Scene::active_floor() const {
    return loaded_->active_floor;
}
double Scene::time() const {
    return loaded_->time;
}
const LoadStatistics& Scene::load_statistics() const {
    return loaded_->load;
}
std::vector<ImageInfo> Scene::render_targets() const {
    return infos_of(loaded_->compositor->targets_held());
}
std::vector<ImageInfo> Scene::images_held() const {
    return infos_of(loaded_->compositor->images_held());
}

Result<void> Scene::set_active_floor(uint32_t floor) {
    if (floor >= floor_count())
        return Error{fmt::format("{}: floor {} does not exist (floors 0..{})",
                                 loaded_->desc.file.string(), floor, floor_count() - 1)};
    loaded_->active_floor = floor;
    return {};
}

Result<void> Scene::set_time(double seconds) {
    if (!std::isfinite(seconds) || std::abs(seconds) > double(std::numeric_limits<float>::max()))
        return Error{
            fmt::format("time: expected a finite number of seconds within the 32-bit "
                        "float range, got {}",
                        seconds)};
    loaded_->time = seconds;
    return {};
}

Result<FrameStatistics> Scene::render() {
    VulkanContext& context = *loaded_->host->context;
    const size_t messages_before = context.validation_messages().size();
    auto stats = loaded_->compositor->render(loaded_->active_floor, loaded_->time);
    if (!stats) return error_of(stats.error());
    if (const size_t after = context.validation_messages().size(); after != messages_before)
        return Error{
            fmt::format("{}: {} Vulkan validation messages during the frame, the first: {}",
                        loaded_->desc.file.string(), after - messages_before,
                        context.validation_messages()[messages_before])};
    loaded_->rendered = true;
    FrameStatistics out;
    out.active_floor = stats->active_floor;
    out.time = loaded_->time;
    out.milliseconds = stats->milliseconds;
    out.passes = stats->passes;
    out.pixels_shaded = stats->pixels_shaded;
    out.violations = stats->violations;
    out.images_loaded = stats->images_loaded;
    out.targets_allocated = stats->targets_allocated;
    out.shaders_compiled = stats->shaders_compiled;
    out.pipelines_created = stats->pipelines_created;
    for (const FloorFrameReport& floor : stats->floors) out.floors.push_back(step_of(floor));
    if (stats->global) out.global_effects = step_of(*stats->global);
    return out;
}

Result<Image> Scene::read_frame() {
    if (!loaded_->rendered)
        return Error{
            fmt::format("{}: no frame rendered yet (render() first)", loaded_->desc.file.string())};
    auto pixels = loaded_->compositor->read_output();
    if (!pixels) return error_of(pixels.error());
    return Image{pixels->width, pixels->height, std::move(pixels->pixels)};
}

Result<void> Scene::write_frame(const std::filesystem::path& file) {
    const std::string ext = file.extension().string();
    if (ext != ".exr" && ext != ".png")
        return Error{fmt::format("{}: a frame is written as .exr or .png", file.string())};
    if (!loaded_->rendered)
        return Error{
            fmt::format("{}: no frame rendered yet (render() first)", loaded_->desc.file.string())};
    auto pixels = loaded_->compositor->read_output();
    if (!pixels) return error_of(pixels.error());
    if (auto saved = save_image(file, pixels.value()); !saved) return error_of(saved.error());
    return {};
}

}  // namespace acetate::host
