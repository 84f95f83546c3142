// The embedding API (acetate/host/host.hpp) on the host's internals: the Vulkan context, the
// renderer (plugin loader, pipeline pool) and one Compositor per scene. This file only
// translates: options in, statistics and errors out; the work is the compositor's.
#include "acetate/host/host.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "load_policy.hpp"
#include "render/compositor.hpp"
#include "render/renderer.hpp"
#include "scene/image_io.hpp"
#include "scene/scene.hpp"
#include "vulkan/pipeline_cache_file.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::host {

// The device and the renderer outlive every scene loaded on them: each Scene holds this.
struct Host::State {
    std::unique_ptr<VulkanContext> context;
    std::unique_ptr<Renderer> renderer;
    std::function<void(const std::string&)> warn;
};

struct Scene::Loaded {
    std::shared_ptr<Host::State> host;
    SceneDesc desc;
    std::unique_ptr<Compositor> compositor;
    LoadStatistics load;
    uint32_t active_floor = 0;
    double time = 0;
    bool rendered = false;
};

namespace {

Error error_of(const acetate::Error& e) {
    return Error{e.message};
}

}  // namespace

Host::Host(std::shared_ptr<State> state) : state_(std::move(state)) {}
Host::~Host() = default;

Result<std::unique_ptr<Host>> Host::create(const HostOptions& options) {
    auto state = std::make_shared<State>();
    state->warn = options.on_warning ? options.on_warning : [](const std::string& line) {
        std::fprintf(stderr, "acetate: %s\n", line.c_str());
    };
    // The policy first: a malformed registry is the caller's input, found before the device.
    LoadPolicyOptions policy_options;
    policy_options.registry = options.registry;
    policy_options.allowed_signers = options.allowed_signers;
    policy_options.allow_unvalidated = options.allow_unvalidated;
    policy_options.allow_hint = "set HostOptions::allow_unvalidated";
    policy_options.warn = state->warn;
    auto policy = LoadPolicy::open(std::move(policy_options));
    if (!policy) return error_of(policy.error());

    ContextOptions context_options = ContextOptions::from_environment();
    if (!options.device.empty()) context_options.device_selector = options.device;
    context_options.validation = context_options.validation || options.validation;
    auto context = VulkanContext::create(context_options);
    if (!context) return error_of(context.error());
    state->context = std::move(context.value());

    RendererOptions renderer_options;
    renderer_options.plugin_directories =
        PluginLoader::default_directories(options.plugin_directories);
    if (options.pipeline_cache)
        renderer_options.pipeline_cache_file = default_pipeline_cache_path();
    auto renderer = Renderer::create(*state->context, renderer_options);
    if (!renderer) return error_of(renderer.error());
    state->renderer = std::move(renderer.value());
    state->renderer->plugins().set_admission(
        [policy = std::move(policy.value())](
            const std::string& id, const std::filesystem::path& file,
            const std::filesystem::path& contents) { return policy.admit(id, file, contents); });
    return std::unique_ptr<Host>(new Host(std::move(state)));
}

std::string Host::device_name() const {
    return state_->context->device_name();
}

Result<void> Host::save_pipeline_cache() {
    if (auto saved = state_->renderer->save_pipeline_cache(); !saved)
        return error_of(saved.error());
    return {};
}

namespace {

Result<std::unique_ptr<Scene::Loaded>> load(const std::shared_ptr<Host::State>& host,
                                            acetate::Result<SceneDesc> parsed) {
    if (!parsed) return error_of(parsed.error());
    auto loaded = std::make_unique<Scene::Loaded>();
    loaded->host = host;
    loaded->desc = std::move(parsed.value());
    CompositorOptions options;  // the picture, half-float targets, every optimisation
    auto compositor = Compositor::load(*host->renderer, loaded->desc, options);
    if (!compositor) return error_of(compositor.error());
    loaded->compositor = std::move(compositor.value());
    const LoadStats& s = loaded->compositor->load_stats();
    loaded->load = {s.milliseconds, s.images_loaded, s.targets_allocated, s.shaders_compiled,
                    s.pipelines_created};
    if (s.tile_texel_violations)
        host->warn(
            fmt::format("warning: {}: {} tile texels have colour at alpha 0 (or NaN/Inf); "
                        "they are dropped",
                        loaded->desc.file.string(), s.tile_texel_violations));
    loaded->active_floor = loaded->desc.active_floor;
    return loaded;
}

}  // namespace

Result<std::unique_ptr<Scene>> Host::load_scene_file(const std::filesystem::path& file) {
    auto loaded = load(state_, parse_scene_file(file));
    if (!loaded) return loaded.error();
    return std::unique_ptr<Scene>(new Scene(std::move(loaded.value())));
}

Result<std::unique_ptr<Scene>> Host::load_scene_text(const std::string& json,
                                                     const std::filesystem::path& base_directory,
                                                     const std::string& name) {
    auto loaded = load(state_, parse_scene_text(json, base_directory / name));
    if (!loaded) return loaded.error();
    return std::unique_ptr<Scene>(new Scene(std::move(loaded.value())));
}

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
