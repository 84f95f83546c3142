#include "render_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include "core/atomic_file.hpp"
#include "load_policy.hpp"
#include "output_paths.hpp"
#include "plugins/plugin_loader.hpp"
#include "registry_location.hpp"
#include "render/compositor.hpp"
#include "render/renderer.hpp"
#include "scene/image_io.hpp"
#include "scene/scene.hpp"
#include "vulkan/pipeline_cache_file.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {
namespace {

int fail(const Error& error) {
    std::fprintf(stderr, "acetate: %s\n", error.message.c_str());
    return 1;
}

int fail(const std::string& message) {
    std::fprintf(stderr, "acetate: %s\n", message.c_str());
    return 1;
}

std::filesystem::path with_suffix(const std::filesystem::path& output, const std::string& suffix) {
    std::filesystem::path p = output;
    p.replace_filename(output.stem().string() + suffix + output.extension().string());
    return p;
}

bool names_a_plugin(const SceneDesc& scene) {
    return !scene.global_effects.empty() ||
           std::any_of(scene.floors.begin(), scene.floors.end(),
                       [](const FloorDesc& f) { return !f.effects.empty(); });
}

// The active floors a scene is rendered from, in order: --floors, --floors all, --floor, or the
// scene's own active floor.
std::vector<uint32_t> floors_to_render(const RenderCommand& command, const SceneDesc& scene) {
    std::vector<uint32_t> floors = command.floors;
    if (command.all_floors)
        for (uint32_t f = 0; f < scene.floors.size(); ++f) floors.push_back(f);
    if (floors.empty()) floors.push_back(command.floor.value_or(scene.active_floor));
    return floors;
}

// Every file the run will write: one image per scene and floor, and the statistics.
std::vector<RunFile> run_outputs(const RenderCommand& command,
                                 const std::vector<SceneDesc>& scenes) {
    std::vector<RunFile> out;
    const bool several_scenes = scenes.size() > 1;
    for (size_t s = 0; s < scenes.size(); ++s) {
        const std::vector<uint32_t> floors = floors_to_render(command, scenes[s]);
        for (uint32_t f : floors)
            out.push_back({frame_output_path(scene_output_path(command.output, s, several_scenes),
                                             f, floors.size() > 1),
                           "-o"});
    }
    if (command.stats) out.push_back({*command.stats, "--stats"});
    return out;
}

// Every file the run reads before it writes: the scenes, their images and masks, the registry.
std::vector<RunFile> run_inputs(const RenderCommand& command,
                                const std::vector<SceneDesc>& scenes) {
    std::vector<RunFile> in;
    for (const SceneDesc& scene : scenes) {
        in.push_back({scene.file, "scene"});
        for (size_t f = 0; f < scene.floors.size(); ++f)
            for (size_t t = 0; t < scene.floors[f].tiles.size(); ++t) {
                const TileDesc& tile = scene.floors[f].tiles[t];
                const std::string where =
                    fmt::format("{}: floors[{}].tiles[{}]", scene.file.string(), f, t);
                in.push_back({tile.image, where + ".image"});
                for (const auto& [kind, mask] : tile.masks)
                    in.push_back({mask, fmt::format("{}.masks.{}", where, kind)});
            }
    }
    in.push_back({registry_path(command.registry), "the registry"});
    in.push_back({allowed_signers_path(command.allowed_signers), "the allowed signers"});
    return in;
}

}  // namespace

std::filesystem::path frame_output_path(const std::filesystem::path& output, uint32_t floor,
                                        bool several) {
    return several ? with_suffix(output, fmt::format(".floor{}", floor)) : output;
}

std::filesystem::path scene_output_path(const std::filesystem::path& output, size_t scene,
                                        bool several) {
    return several ? with_suffix(output, fmt::format(".scene{}", scene)) : output;
}

int run_render(const RenderCommand& command) {
    // Exactly ".exr" or ".png", as documented; ".PNG" is refused rather than guessed at.
    const std::string ext = command.output.extension().string();
    if (ext != ".exr" && ext != ".png")
        return fail(
            fmt::format("-o {}: the output must end in .exr or .png", command.output.string()));
    // Effects also read the time as a 32-bit float (acetate_time), which must stay finite.
    if (!std::isfinite(command.time) ||
        std::abs(command.time) > double(std::numeric_limits<float>::max()))
        return fail(
            fmt::format("--time: expected a finite number of seconds within the 32-bit "
                        "float range, got {}",
                        command.time));
    auto view = parse_view(command.view);
    if (!view) return fail(view.error());
    CompositorOptions options;
    options.view = view.value();
    if (command.format == "rgba16f")
        options.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    else if (command.format == "rgba32f")
        options.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    else
        return fail(
            fmt::format("--format: expected rgba16f or rgba32f, got \"{}\"", command.format));

    // Every scene is parsed and checked before the device starts: bad input fails fast.
    std::vector<SceneDesc> scenes;
    for (const auto& file : command.scenes) {
        auto scene = parse_scene_file(file);
        if (!scene) return fail(scene.error());
        for (uint32_t f : command.floors)
            if (f >= scene->floors.size())
                return fail(fmt::format("--floors: floor {} does not exist in {} (floors 0..{})", f,
                                        file.string(), scene->floors.size() - 1));
        if (command.floor && *command.floor >= scene->floors.size())
            return fail(fmt::format("--floor: floor {} does not exist in {} (floors 0..{})",
                                    *command.floor, file.string(), scene->floors.size() - 1));
        scenes.push_back(std::move(scene.value()));
    }
    // The registry is read once, and only when some scene names a plugin: a scene without
    // effects involves no policy. A malformed registry is bad input like a malformed scene.
    std::optional<LoadPolicy> policy;
    if (std::any_of(scenes.begin(), scenes.end(), names_a_plugin)) {
        LoadPolicyOptions policy_options;
        policy_options.registry = command.registry;
        policy_options.allowed_signers = command.allowed_signers;
        policy_options.allow_unvalidated = command.allow_unvalidated;
        policy_options.warn = [](const std::string& line) {
            std::fprintf(stderr, "acetate: %s\n", line.c_str());
        };
        auto opened = LoadPolicy::open(std::move(policy_options));
        if (!opened) return fail(opened.error());
        policy = std::move(opened.value());
    }
    if (auto spared =
            check_outputs_spare_inputs(run_outputs(command, scenes), run_inputs(command, scenes));
        !spared)
        return fail(spared.error());

    auto context = VulkanContext::create(ContextOptions::from_environment());
    if (!context) return fail(context.error());
    std::printf("device: %s\n", (*context)->device_name().c_str());
    RendererOptions renderer_options;
    renderer_options.plugin_directories = PluginLoader::default_directories(command.plugin_paths);
    if (command.pipeline_cache)
        renderer_options.pipeline_cache_file = default_pipeline_cache_path();
    auto renderer = Renderer::create(*context.value(), renderer_options);
    if (!renderer) return fail(renderer.error());
    if (policy)
        (*renderer)->plugins().set_admission(
            [policy = std::move(*policy)](const std::string& id, const std::filesystem::path& file,
                                          const std::filesystem::path& contents) {
                return policy.admit(id, file, contents);
            });

    nlohmann::json scene_reports = nlohmann::json::array();
    const bool several_scenes = scenes.size() > 1;
    int failed_scenes = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
        const SceneDesc& scene = scenes[s];
        auto compositor = Compositor::load(*renderer.value(), scene, options);
        if (!compositor) {
            // A scene that cannot load (a broken plugin, say) is reported; the host goes on
            // with the other scenes and exits non-zero at the end.
            fail(compositor.error());
            ++failed_scenes;
            scene_reports.push_back(
                {{"scene", scene.file.string()}, {"error", compositor.error().message}});
            continue;
        }
        const LoadStats& load = (*compositor)->load_stats();
        std::printf(
            "loaded %s in %.1f ms: %llu images, %llu targets, %llu shaders compiled, "
            "%llu pipelines created\n",
            scene.file.string().c_str(), load.milliseconds, (unsigned long long)load.images_loaded,
            (unsigned long long)load.targets_allocated, (unsigned long long)load.shaders_compiled,
            (unsigned long long)load.pipelines_created);
        if (load.tile_texel_violations)
            std::fprintf(stderr,
                         "acetate: warning: %s: %llu tile texels have colour at alpha 0 (or "
                         "NaN/Inf); they are dropped\n",
                         scene.file.string().c_str(),
                         (unsigned long long)load.tile_texel_violations);

        const std::vector<uint32_t> floors = floors_to_render(command, scene);
        const bool several_floors = floors.size() > 1;
        nlohmann::json frames = nlohmann::json::array();
        for (size_t i = 0; i < floors.size(); ++i) {
            auto stats = (*compositor)->render(floors[i], command.time);
            if (!stats) return fail(stats.error());
            auto pixels = (*compositor)->read_output();
            if (!pixels) return fail(pixels.error());
            const auto path = frame_output_path(
                scene_output_path(command.output, s, several_scenes), floors[i], several_floors);
            if (auto saved = save_image(path, pixels.value()); !saved) return fail(saved.error());
            std::printf(
                "[%zu/%zu] floor %u: %.2f ms, %u passes, %llu pixels shaded, %llu "
                "violations -> %s\n",
                i + 1, floors.size(), floors[i], stats->milliseconds, stats->passes,
                (unsigned long long)stats->pixels_shaded, (unsigned long long)stats->violations,
                path.string().c_str());
            frames.push_back(to_json(stats.value()));
        }
        nlohmann::json targets = nlohmann::json::array();
        for (const TargetInfo& t : (*compositor)->targets_held()) targets.push_back(to_json(t));
        nlohmann::json images = nlohmann::json::array();
        for (const TargetInfo& t : (*compositor)->images_held()) images.push_back(to_json(t));
        scene_reports.push_back({{"scene", scene.file.string()},
                                 {"load", to_json(load)},
                                 {"load_milliseconds", load.milliseconds},
                                 {"frames", frames},
                                 {"render_targets", targets},
                                 {"images_held", images}});
    }
    if (auto saved = (*renderer)->save_pipeline_cache(); !saved)
        std::fprintf(stderr, "acetate: warning: pipeline cache not saved: %s\n",
                     saved.error().message.c_str());

    if (command.stats) {
        // The first scene's figures stay at the top level, as for a single scene.
        nlohmann::json stats = scene_reports.front();
        stats["device"] = (*context)->device_name();
        stats["view"] = command.view;
        stats["format"] = command.format;
        stats["scenes"] = scene_reports;
        stats["plugins_loaded"] = (*renderer)->plugins().loaded_count();
        stats["pipelines_in_pool"] = (*renderer)->pool().pipeline_count();
        stats["pipeline_cache_warning"] = (*renderer)->pipeline_cache_warning();
        stats["validation_messages"] = (*context)->validation_messages().size();
        if (auto written = write_file_atomically(*command.stats, stats.dump(2) + "\n"); !written)
            return fail(written.error());
        std::printf("stats -> %s\n", command.stats->string().c_str());
    }
    if (!(*context)->validation_messages().empty())
        return fail(fmt::format("{} Vulkan validation messages (see above)",
                                (*context)->validation_messages().size()));
    return failed_scenes ? 1 : 0;
}

}  // namespace acetate
