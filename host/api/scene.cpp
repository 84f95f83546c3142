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

// What a live change (ParamChange, CameraChange) did on the device since `before`, and its time.
template <class Change>
void record_cost(Change& change, VulkanContext& context, const ResourceCounters& before,
                 std::chrono::steady_clock::time_point start) {
    const ResourceCounters used = context.counters() - before;
    change.images_loaded = used.images_loaded;
    change.targets_allocated = used.targets_allocated;
    change.shaders_compiled = used.shaders_compiled;
    change.pipelines_created = used.pipelines_created;
    change.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
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
        auto compositor = load_again(loaded, desc);
        if (!compositor) return error_of(compositor.error());
        loaded.compositor = std::move(compositor.value());
        loaded.desc = std::move(desc);
        loaded.rendered = false;  // read_frame() wants a frame of this scene
        change.reloaded = true;
    }
    record_cost(change, *loaded.host->context, before, start);
    return change;
}

// The view a camera asks for, each number read and checked here: the origin within 2^24
// scene pixels (whole numbers up to there are exact in a shader's float), a region of positive
// size, a scale from 1/64 to 64, an output of round(width * scale) x round(height * scale)
// pixels, at least 1 and at most 65536 per side (the device may allow fewer: the compositor
// checks its limit).
Result<ViewTransform> view_of(const Camera& camera, const std::string& scene) {
    constexpr double kMaxOrigin = 16777216.0, kMinScale = 1.0 / 64, kMaxScale = 64;
    auto refuse = [&](const std::string& what) {
        return Error{fmt::format("{}: camera: {}", scene, what)};
    };
    if (!std::isfinite(camera.x) || !std::isfinite(camera.y) || std::abs(camera.x) > kMaxOrigin ||
        std::abs(camera.y) > kMaxOrigin)
        return refuse(fmt::format("origin ({}, {}): expected finite numbers within +-16777216",
                                  camera.x, camera.y));
    if (!std::isfinite(camera.scale) || camera.scale < kMinScale || camera.scale > kMaxScale)
        return refuse(fmt::format("scale {}: expected a number from 1/64 to 64", camera.scale));
    if (!std::isfinite(camera.width) || !std::isfinite(camera.height) || camera.width <= 0 ||
        camera.height <= 0)
        return refuse(fmt::format("size {} x {}: expected finite numbers above 0", camera.width,
                                  camera.height));
    const double w = std::round(camera.width * camera.scale);
    const double h = std::round(camera.height * camera.scale);
    if (w < 1 || h < 1 || w > 65536 || h > 65536)
        return refuse(
            fmt::format("an output of {} x {} pixels (size times scale): expected 1 "
                        "to 65536 per side",
                        w, h));
    return ViewTransform{camera.x, camera.y, camera.scale, uint32_t(w), uint32_t(h)};
}

}  // namespace

acetate::Result<std::unique_ptr<Compositor>> load_again(const Scene::Loaded& loaded,
                                                        const SceneDesc& desc) {
    auto compositor = Compositor::load(*loaded.host->renderer, desc, loaded.options);
    if (!compositor) return compositor.error();
    ACETATE_TRY(compositor.value()->set_view_transform(loaded.compositor->view_transform()));
    return compositor;
}

Result<CameraChange> Scene::set_camera(const Camera& camera) {
    const std::lock_guard lock(loaded_->host->calls);
    auto view = view_of(camera, loaded_->desc.file.string());
    if (!view) return view.error();
    const auto start = std::chrono::steady_clock::now();
    const ResourceCounters before = loaded_->host->context->counters();
    const ViewTransform old = loaded_->compositor->view_transform();
    if (auto done = loaded_->compositor->set_view_transform(view.value()); !done)
        return error_of(done.error());
    loaded_->camera = camera;
    CameraChange change;
    change.resized = old.width != view->width || old.height != view->height;
    change.rebuilt = change.resized || old.scale != view->scale;
    if (view.value() != old) loaded_->rendered = false;  // read_frame() wants a frame of it
    record_cost(change, *loaded_->host->context, before, start);
    return change;
}

Camera Scene::camera() const {
    const std::lock_guard lock(loaded_->host->calls);
    if (loaded_->camera) return *loaded_->camera;
    return Camera{0, 0, double(loaded_->desc.width), double(loaded_->desc.height), 1};
}

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
    out.barriers = stats->barriers;
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
