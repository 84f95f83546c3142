// The embedding API (acetate/host/host.hpp) on the host's internals: the Vulkan context, the
// renderer (plugin loader, pipeline pool) and one Compositor per scene. This file is the Host
// (scene.cpp the Scene); both only translate: options in, statistics and errors out.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "api/host_internal.hpp"
#include "load_policy.hpp"
#include "registry_location.hpp"
#include "vulkan/pipeline_cache_file.hpp"

namespace acetate::host {
namespace {

// The first effect the scene names, or null.
const EffectRef* first_effect(const SceneDesc& scene) {
    for (const FloorDesc& floor : scene.floors)
        if (!floor.effects.empty()) return &floor.effects.front();
    return scene.global_effects.empty() ? nullptr : &scene.global_effects.front();
}

acetate::OutputView internal_view(View view) {
    return acetate::OutputView(int(view));  // the same order (static_asserts below)
}
static_assert(int(ErrorCode::PluginRefused) == int(acetate::ErrorCode::PluginRefused) &&
              int(ErrorCode::InvalidInput) == int(acetate::ErrorCode::InvalidInput) &&
              int(ErrorCode::ShaderCompile) == int(acetate::ErrorCode::ShaderCompile));
static_assert(int(View::Isolation) == int(acetate::OutputView::Isolation) &&
              int(View::FloorRgb) == int(acetate::OutputView::FloorRgb));

Result<std::unique_ptr<Scene::Loaded>> load(const std::shared_ptr<Host::State>& host,
                                            acetate::Result<SceneDesc> parsed,
                                            const SceneOptions& scene_options) {
    if (!parsed) return error_of(parsed.error());
    // Refused before any plugin file is looked for: whether it exists does not matter.
    if (const EffectRef* effect = first_effect(parsed.value()); effect && !host->load_plugins)
        return Error{
            fmt::format("{}: {}.plugin: this host loads no plugins "
                        "(HostOptions::load_plugins is off)",
                        parsed->file.string(), effect->where)};
    const std::lock_guard lock(host->calls);
    auto loaded = std::make_unique<Scene::Loaded>();
    loaded->host = host;
    loaded->desc = std::move(parsed.value());
    CompositorOptions options;  // every optimisation on
    options.view = internal_view(scene_options.view);
    options.format = scene_options.precision == Precision::Float32 ? VK_FORMAT_R32G32B32A32_SFLOAT
                                                                   : VK_FORMAT_R16G16B16A16_SFLOAT;
    options.leave_out_refused = scene_options.leave_out_refused_effects;
    options.gpu_timings = scene_options.gpu_timings;
    auto compositor = Compositor::load(*host->renderer, loaded->desc, options);
    if (!compositor) return error_of(compositor.error());
    loaded->compositor = std::move(compositor.value());
    loaded->options = options;
    const LoadStats& s = loaded->compositor->load_stats();
    loaded->load = {s.milliseconds,     s.images_loaded,     s.targets_allocated,
                    s.shaders_compiled, s.pipelines_created, s.tile_texel_violations};
    if (s.tile_texel_violations)
        host->warn(
            fmt::format("warning: {}: {} tile texels have colour at alpha 0 (or NaN/Inf); "
                        "they are dropped",
                        loaded->desc.file.string(), s.tile_texel_violations));
    for (const LeftOutEntry& e : loaded->compositor->left_out())
        host->warn(fmt::format("warning: loaded without {}: {}", e.plugin, e.message));
    loaded->active_floor = loaded->desc.active_floor;
    return loaded;
}

}  // namespace

Result<View> parse_view(const std::string& name) {
    auto view = acetate::parse_view(name);
    if (!view) return error_of(view.error());
    return View(int(view.value()));
}

const char* view_name(View view) {
    return acetate::to_string(internal_view(view));
}

Host::Host(std::shared_ptr<State> state) : state_(std::move(state)) {}
Host::~Host() = default;

std::filesystem::path Host::registry_file(const HostOptions& options) {
    return registry_path(options.registry);
}

std::filesystem::path Host::allowed_signers_file(const HostOptions& options) {
    return allowed_signers_path(options.allowed_signers);
}

Result<SceneInfo> Host::inspect_scene_file(const std::filesystem::path& file) {
    auto scene = parse_scene_file(file);
    if (!scene) return error_of(scene.error());
    SceneInfo info;
    info.file = scene->file;
    info.width = scene->width;
    info.height = scene->height;
    info.active_floor = scene->active_floor;
    info.names_plugins = first_effect(scene.value()) != nullptr;
    info.inputs.push_back({scene->file, "scene"});
    for (size_t f = 0; f < scene->floors.size(); ++f) {
        const FloorDesc& floor = scene->floors[f];
        info.floor_names.push_back(floor.name);
        info.floor_effects.emplace_back();
        for (const EffectRef& ref : floor.effects) info.floor_effects.back().push_back(ref.plugin);
        for (size_t t = 0; t < floor.tiles.size(); ++t) {
            const TileDesc& tile = floor.tiles[t];
            const std::string where =
                fmt::format("{}: floors[{}].tiles[{}]", scene->file.string(), f, t);
            info.inputs.push_back({tile.image, where + ".image"});
            for (const auto& [kind, mask] : tile.masks)
                info.inputs.push_back({mask, fmt::format("{}.masks.{}", where, kind)});
        }
    }
    for (const EffectRef& ref : scene->global_effects) info.global_effects.push_back(ref.plugin);
    return info;
}

Result<std::unique_ptr<Host>> Host::create(const HostOptions& options) {
    auto state = std::make_shared<State>();
    state->warn = options.on_warning ? options.on_warning : [](const std::string& line) {
        std::fprintf(stderr, "acetate: %s\n", line.c_str());
    };
    state->load_plugins = options.load_plugins;
    // The policy first: a malformed registry is the caller's input, found before the device.
    std::optional<LoadPolicy> policy;
    if (options.load_plugins) {
        LoadPolicyOptions policy_options;
        policy_options.registry = options.registry;
        policy_options.allowed_signers = options.allowed_signers;
        policy_options.allow_unvalidated = options.allow_unvalidated;
        policy_options.allow_hint = options.allow_unvalidated_hint;
        policy_options.warn = state->warn;
        auto opened = LoadPolicy::open(std::move(policy_options));
        if (!opened) return error_of(opened.error());
        policy = std::move(opened.value());
    }

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
    if (policy)
        state->renderer->plugins().set_admission(
            [policy = std::move(*policy)](const std::string& id, const std::filesystem::path& file,
                                          const std::filesystem::path& contents) {
                return policy.admit(id, file, contents);
            });
    else
        state->renderer->plugins().set_admission(
            [](const std::string& id, const std::filesystem::path& file,
               const std::filesystem::path&) -> acetate::Result<void> {
                return make_error(acetate::ErrorCode::InvalidInput,
                                  fmt::format("plugin {} ({}): this host loads no plugins "
                                              "(HostOptions::load_plugins is off)",
                                              id, file.string()));
            });
    return std::unique_ptr<Host>(new Host(std::move(state)));
}

std::string Host::device_name() const {
    return state_->context->device_name();
}

namespace {

bool scene_uses(const SceneDesc& scene, const std::string& id) {
    const auto named = [&](const EffectRef& ref) { return ref.plugin == id; };
    return std::any_of(scene.global_effects.begin(), scene.global_effects.end(), named) ||
           std::any_of(scene.floors.begin(), scene.floors.end(), [&](const FloorDesc& floor) {
               return std::any_of(floor.effects.begin(), floor.effects.end(), named);
           });
}

}  // namespace

std::vector<PluginReload> Host::reload_plugins() {
    const std::lock_guard lock(state_->calls);
    std::vector<PluginReload> reloads;
    for (PluginReloadOutcome& outcome : state_->renderer->plugins().reload_changed()) {
        PluginReload reload{outcome.id, outcome.file, outcome.changed, 0, ""};
        if (outcome.refused) reload.refused = outcome.refused->message;
        if (outcome.changed && !outcome.refused) {
            for (Scene::Loaded* loaded : state_->scenes) {
                // The scene as it renders now, live parameters included.
                SceneDesc desc = loaded->compositor->scene();
                if (!scene_uses(desc, outcome.id)) continue;
                auto compositor = load_again(*loaded, desc);
                if (!compositor) {
                    reload.refused +=
                        (reload.refused.empty() ? "" : "; ") + compositor.error().message;
                    continue;
                }
                loaded->compositor = std::move(compositor.value());
                loaded->desc = std::move(desc);
                loaded->rendered = false;  // read_frame() wants a frame of the new code
                ++reload.scenes_rebuilt;
            }
        }
        if (!reload.refused.empty())
            state_->warn(fmt::format("warning: {} ({}) not reloaded: {}", reload.plugin,
                                     reload.file.string(), reload.refused));
        reloads.push_back(std::move(reload));
    }
    return reloads;
}

Result<void> Host::save_pipeline_cache() {
    const std::lock_guard lock(state_->calls);
    if (auto saved = state_->renderer->save_pipeline_cache(); !saved)
        return error_of(saved.error());
    return {};
}

std::string Host::pipeline_cache_warning() const {
    const std::lock_guard lock(state_->calls);
    return state_->renderer->pipeline_cache_warning();
}

uint32_t Host::plugins_loaded() const {
    const std::lock_guard lock(state_->calls);
    return uint32_t(state_->renderer->plugins().loaded_count());
}

uint32_t Host::pipelines_in_pool() const {
    const std::lock_guard lock(state_->calls);
    return uint32_t(state_->renderer->pool().pipeline_count());
}

uint32_t Host::validation_messages() const {
    const std::lock_guard lock(state_->calls);
    return uint32_t(state_->context->validation_messages().size());
}

Result<std::unique_ptr<Scene>> Host::load_scene_file(const std::filesystem::path& file,
                                                     const SceneOptions& options) {
    auto loaded = load(state_, parse_scene_file(file), options);
    if (!loaded) return loaded.error();
    return std::unique_ptr<Scene>(new Scene(std::move(loaded.value())));
}

Result<std::unique_ptr<Scene>> Host::load_scene_text(const std::string& json,
                                                     const std::filesystem::path& base_directory,
                                                     const std::string& name,
                                                     const SceneOptions& options) {
    auto loaded = load(state_, parse_scene_text(json, base_directory / name), options);
    if (!loaded) return loaded.error();
    return std::unique_ptr<Scene>(new Scene(std::move(loaded.value())));
}

}  // namespace acetate::host
