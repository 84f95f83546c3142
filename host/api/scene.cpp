// The embedding API's Scene (acetate/host/host.hpp): one Compositor, its active floor and
// time, and its statistics in the API's own types.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>

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

// Gives one effect of the scene the entry `edit` makes of its current one: in place when its
// build() declares the same graph, by building that effect again when it declares another,
// and by loading the scene again only when the floor's plan depends on the change (the old
// scene keeps rendering if anything fails).
Result<ParamChange> change_effect(Scene::Loaded& loaded, const EffectSlot& slot,
                                  const std::function<void(EffectRef&)>& edit) {
    const auto start = std::chrono::steady_clock::now();
    const ResourceCounters before = loaded.host->context->counters();
    auto current = loaded.compositor->effect_ref(slot.floor, slot.index);
    if (!current) return error_of(current.error());
    EffectRef ref = std::move(current.value());
    edit(ref);
    auto done = loaded.compositor->set_effect_ref(slot.floor, slot.index, ref);
    if (!done) return error_of(done.error());
    ParamChange change;
    change.rebuilt = done.value() == Compositor::EffectChange::Rebuilt;
    if (done.value() == Compositor::EffectChange::NeedsLoad) {
        SceneDesc desc = loaded.compositor->scene();
        (slot.floor ? desc.floors[*slot.floor].effects : desc.global_effects)[slot.index] = ref;
        auto compositor = Compositor::load(*loaded.host->renderer, desc, loaded.options);
        if (!compositor) return error_of(compositor.error());
        loaded.compositor = std::move(compositor.value());
        loaded.desc = std::move(desc);
        loaded.rendered = false;  // read_frame() wants a frame of this scene
        change.reloaded = true;
    }
    const ResourceCounters used = loaded.host->context->counters() - before;
    change.images_loaded = used.images_loaded;
    change.targets_allocated = used.targets_allocated;
    change.shaders_compiled = used.shaders_compiled;
    change.pipelines_created = used.pipelines_created;
    change.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return change;
}

}  // namespace

Result<ParamChange> Scene::set_param(const EffectSlot& effect, const std::string& name,
                                     const std::vector<float>& value) {
    const std::lock_guard lock(loaded_->host->calls);
    return change_effect(*loaded_, effect, [&](EffectRef& ref) {
        // As the scene file would say it: a number, or an array of 2 or 3.
        ref.params[name] = value.size() == 1
                               ? nlohmann::json(double(value[0]))
                               : nlohmann::json(std::vector<double>(value.begin(), value.end()));
    });
}

Result<ParamChange> Scene::set_preset(const EffectSlot& effect, const std::string& preset) {
    const std::lock_guard lock(loaded_->host->calls);
    return change_effect(*loaded_, effect, [&](EffectRef& ref) { ref.preset = preset; });
}

Scene::Scene(std::unique_ptr<Loaded> loaded) : loaded_(std::move(loaded)) {
    const std::lock_guard lock(loaded_->host->calls);
    loaded_->host->scenes.push_back(loaded_.get());
}
// The compositor goes first: it uses the renderer and device the Loaded keeps alive.
Scene::~Scene() {
    if (!loaded_) return;
    // Released before loaded_ goes: it may hold the last reference to the lock's Host::State.
    const std::lock_guard lock(loaded_->host->calls);
    std::erase(loaded_->host->scenes, loaded_.get());
    loaded_->compositor.reset();
}

uint32_t Scene::width() const {
    const std::lock_guard lock(loaded_->host->calls);
    return loaded_->desc.width;
}
uint32_t Scene::height() const {
    const std::lock_guard lock(loaded_->host->calls);
    return loaded_->desc.height;
}
uint32_t Scene::floor_count() const {
    const std::lock_guard lock(loaded_->host->calls);
    return uint32_t(loaded_->desc.floors.size());
}
std::string Scene::floor_name(uint32_t floor) const {
    const std::lock_guard lock(loaded_->host->calls);
    return floor < loaded_->desc.floors.size() ? loaded_->desc.floors[floor].name : std::string();
}
uint32_t Scene::active_floor() const {
    const std::lock_guard lock(loaded_->host->calls);
    return loaded_->active_floor;
}
double Scene::time() const {
    const std::lock_guard lock(loaded_->host->calls);
    return loaded_->time;
}
const LoadStatistics& Scene::load_statistics() const {
    return loaded_->load;
}
std::vector<LeftOutEffect> Scene::left_out_effects() const {
    const std::lock_guard lock(loaded_->host->calls);
    std::vector<LeftOutEffect> out;
    for (const LeftOutEntry& e : loaded_->compositor->left_out())
        out.push_back({{e.floor, e.index}, e.plugin, e.message});
    return out;
}
std::vector<ImageInfo> Scene::render_targets() const {
    const std::lock_guard lock(loaded_->host->calls);
    return infos_of(loaded_->compositor->targets_held());
}
std::vector<ImageInfo> Scene::images_held() const {
    const std::lock_guard lock(loaded_->host->calls);
    return infos_of(loaded_->compositor->images_held());
}

Result<void> Scene::set_active_floor(uint32_t floor) {
    const std::lock_guard lock(loaded_->host->calls);
    const size_t floors = loaded_->desc.floors.size();
    if (floor >= floors)
        return Error{fmt::format("{}: floor {} does not exist (floors 0..{})",
                                 loaded_->desc.file.string(), floor, floors - 1)};
    loaded_->active_floor = floor;
    return {};
}

Result<void> Scene::set_time(double seconds) {
    const std::lock_guard lock(loaded_->host->calls);
    if (!std::isfinite(seconds) || std::abs(seconds) > double(std::numeric_limits<float>::max()))
        return Error{
            fmt::format("time: expected a finite number of seconds within the 32-bit "
                        "float range, got {}",
                        seconds)};
    loaded_->time = seconds;
    return {};
}

Result<FrameStatistics> Scene::render() {
    const std::lock_guard lock(loaded_->host->calls);
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
    for (const PassTiming& pass : stats->gpu_passes)
        out.gpu_passes.push_back({pass.name, pass.milliseconds});
    return out;
}

std::string Scene::gpu_timings_warning() const {
    const std::lock_guard lock(loaded_->host->calls);
    return loaded_->compositor->gpu_timings_warning();
}

Result<Image> Scene::read_frame() {
    const std::lock_guard lock(loaded_->host->calls);
    if (!loaded_->rendered)
        return Error{
            fmt::format("{}: no frame rendered yet (render() first)", loaded_->desc.file.string())};
    auto pixels = loaded_->compositor->read_output();
    if (!pixels) return error_of(pixels.error());
    return Image{pixels->width, pixels->height, std::move(pixels->pixels)};
}

Result<void> Scene::write_frame(const std::filesystem::path& file) {
    const std::lock_guard lock(loaded_->host->calls);
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
