#include "render_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "acetate/host/host.hpp"
#include "core/atomic_file.hpp"
#include "core/output_paths.hpp"
#include "stats_json.hpp"

// A thin program on the embedding API (acetate/host/host.hpp): the flags become HostOptions
// and SceneOptions, the API loads and renders, and this file prints progress and writes the
// statistics. Only checking outputs against inputs and writing files atomically are its own.
namespace acetate {
namespace {

int fail(const std::string& message) {
    std::fprintf(stderr, "acetate: %s\n", message.c_str());
    return 1;
}

std::filesystem::path with_suffix(const std::filesystem::path& output, const std::string& suffix) {
    std::filesystem::path p = output;
    p.replace_filename(output.stem().string() + suffix + output.extension().string());
    return p;
}

// The active floors a scene is rendered from, in order: --floors, --floors all, --floor, or the
// scene's own active floor.
std::vector<uint32_t> floors_to_render(const RenderCommand& command, const host::SceneInfo& scene) {
    std::vector<uint32_t> floors = command.floors;
    if (command.all_floors)
        for (uint32_t f = 0; f < scene.floor_names.size(); ++f) floors.push_back(f);
    if (floors.empty()) floors.push_back(command.floor.value_or(scene.active_floor));
    return floors;
}

// The times each floor is rendered at: --times, or --time alone.
std::vector<double> times_to_render(const RenderCommand& command) {
    return command.times.empty() ? std::vector<double>{command.time} : command.times;
}

// Where frame (scene s, floor f, time index t) goes.
std::filesystem::path output_of(const RenderCommand& command, size_t scenes, size_t s,
                                size_t floors, uint32_t floor, size_t times, size_t t) {
    return time_output_path(
        frame_output_path(scene_output_path(command.output, s, scenes > 1), floor, floors > 1), t,
        times > 1);
}

// Every file the run will write: one image per scene, floor and time, and the statistics.
std::vector<RunFile> run_outputs(const RenderCommand& command,
                                 const std::vector<host::SceneInfo>& scenes) {
    std::vector<RunFile> out;
    const size_t times = times_to_render(command).size();
    for (size_t s = 0; s < scenes.size(); ++s) {
        const std::vector<uint32_t> floors = floors_to_render(command, scenes[s]);
        for (uint32_t f : floors)
            for (size_t t = 0; t < times; ++t)
                out.push_back(
                    {output_of(command, scenes.size(), s, floors.size(), f, times, t), "-o"});
    }
    if (command.stats) out.push_back({*command.stats, "--stats"});
    return out;
}

// Every file the run reads before it writes: the scenes, their images and masks, the registry.
std::vector<RunFile> run_inputs(const std::vector<host::SceneInfo>& scenes,
                                const host::HostOptions& options) {
    std::vector<RunFile> in;
    for (const host::SceneInfo& scene : scenes)
        for (const host::SceneInfo::Input& input : scene.inputs)
            in.push_back({input.file, input.field});
    in.push_back({host::Host::registry_file(options), "the registry"});
    in.push_back({host::Host::allowed_signers_file(options), "the allowed signers"});
    return in;
}

host::HostOptions host_options(const RenderCommand& command, bool load_plugins) {
    host::HostOptions options;
    options.pipeline_cache = command.pipeline_cache;
    options.plugin_directories = command.plugin_paths;
    options.registry = command.registry;
    options.allowed_signers = command.allowed_signers;
    options.allow_unvalidated = command.allow_unvalidated;
    options.allow_unvalidated_hint = "pass --allow-unvalidated";
    // The registry is read only when some scene names a plugin: a scene without effects
    // involves no policy. A malformed registry is bad input like a malformed scene.
    options.load_plugins = load_plugins;
    options.on_warning = [](const std::string& line) {
        std::fprintf(stderr, "acetate: %s\n", line.c_str());
    };
    return options;
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

std::filesystem::path time_output_path(const std::filesystem::path& output, size_t index,
                                       bool several) {
    return several ? with_suffix(output, fmt::format(".frame{:04}", index)) : output;
}

int run_render(const RenderCommand& command) {
    // Exactly ".exr" or ".png", as documented; ".PNG" is refused rather than guessed at.
    const std::string ext = command.output.extension().string();
    if (ext != ".exr" && ext != ".png")
        return fail(
            fmt::format("-o {}: the output must end in .exr or .png", command.output.string()));
    // --time was read finite and within the 32-bit float range (flags::kMaxTimeSeconds).
    host::SceneOptions scene_options;
    auto view = host::parse_view(command.view);
    if (!view) return fail("--view: " + view.error().message);
    scene_options.view = view.value();
    if (command.format == "rgba16f")
        scene_options.precision = host::Precision::Float16;
    else if (command.format == "rgba32f")
        scene_options.precision = host::Precision::Float32;
    else
        return fail(
            fmt::format("--format: expected rgba16f or rgba32f, got \"{}\"", command.format));

    // Every scene is read and checked before the device starts: bad input fails fast.
    std::vector<host::SceneInfo> scenes;
    for (const auto& file : command.scenes) {
        auto scene = host::Host::inspect_scene_file(file);
        if (!scene) return fail(scene.error().message);
        const size_t floor_count = scene->floor_names.size();
        for (uint32_t f : command.floors)
            if (f >= floor_count)
                return fail(fmt::format("--floors: floor {} does not exist in {} (floors 0..{})", f,
                                        file.string(), floor_count - 1));
        for (const ParamFlag& flag : command.params)
            if (auto slot = resolve_param_flag(flag, scene.value()); !slot)
                return fail(slot.error().message);
        if (command.floor && *command.floor >= floor_count)
            return fail(fmt::format("--floor: floor {} does not exist in {} (floors 0..{})",
                                    *command.floor, file.string(), floor_count - 1));
        scenes.push_back(std::move(scene.value()));
    }
    const bool load_plugins =
        std::any_of(scenes.begin(), scenes.end(), [](const auto& s) { return s.names_plugins; });
    const host::HostOptions options = host_options(command, load_plugins);
    if (auto spared =
            check_outputs_spare_inputs(run_outputs(command, scenes), run_inputs(scenes, options));
        !spared)
        return fail(spared.error().message);

    auto created = host::Host::create(options);
    if (!created) return fail(created.error().message);
    host::Host& acetate_host = *created.value();
    std::printf("device: %s\n", acetate_host.device_name().c_str());

    nlohmann::json scene_reports = nlohmann::json::array();
    int failed_scenes = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
        const std::string scene_name = scenes[s].file.string();
        auto scene = acetate_host.load_scene_file(command.scenes[s], scene_options);
        if (!scene) {
            // A scene that cannot load (a broken plugin, say) is reported; the host goes on
            // with the other scenes and exits non-zero at the end.
            fail(scene.error().message);
            ++failed_scenes;
            scene_reports.push_back({{"scene", scene_name}, {"error", scene.error().message}});
            continue;
        }
        for (const ParamFlag& flag : command.params) {
            auto slot = resolve_param_flag(flag, scenes[s]);  // checked above: cannot fail
            auto changed = flag.flag == "--preset"
                               ? (*scene)->set_preset(slot.value(), flag.preset)
                               : (*scene)->set_param(slot.value(), flag.name, flag.value);
            if (!changed) return fail(flag.flag + " " + flag.text + ": " + changed.error().message);
        }
        const host::LoadStatistics& load = (*scene)->load_statistics();
        std::printf(
            "loaded %s in %.1f ms: %llu images, %llu targets, %llu shaders compiled, "
            "%llu pipelines created\n",
            scene_name.c_str(), load.milliseconds, (unsigned long long)load.images_loaded,
            (unsigned long long)load.targets_allocated, (unsigned long long)load.shaders_compiled,
            (unsigned long long)load.pipelines_created);

        const std::vector<uint32_t> floors = floors_to_render(command, scenes[s]);
        const std::vector<double> times = times_to_render(command);
        const size_t total = floors.size() * times.size();
        nlohmann::json frames = nlohmann::json::array();
        for (size_t i = 0; i < total; ++i) {
            const uint32_t floor = floors[i / times.size()];
            const size_t t = i % times.size();
            if (auto set = (*scene)->set_active_floor(floor); !set)
                return fail(set.error().message);
            if (auto set = (*scene)->set_time(times[t]); !set) return fail(set.error().message);
            auto stats = (*scene)->render();
            if (!stats) return fail(stats.error().message);
            const auto path =
                output_of(command, scenes.size(), s, floors.size(), floor, times.size(), t);
            if (auto written = (*scene)->write_frame(path); !written)
                return fail(written.error().message);
            std::printf(
                "[%zu/%zu] floor %u%s: %.2f ms, %u passes, %llu pixels shaded, %llu "
                "violations -> %s\n",
                i + 1, total, floor,
                times.size() > 1 ? fmt::format(" at {} s", times[t]).c_str() : "",
                stats->milliseconds, stats->passes, (unsigned long long)stats->pixels_shaded,
                (unsigned long long)stats->violations, path.string().c_str());
            nlohmann::json frame = to_json(stats.value());
            frame["time"] = times[t];
            frames.push_back(std::move(frame));
        }
        nlohmann::json targets = nlohmann::json::array();
        for (const host::ImageInfo& t : (*scene)->render_targets()) targets.push_back(to_json(t));
        nlohmann::json images = nlohmann::json::array();
        for (const host::ImageInfo& t : (*scene)->images_held()) images.push_back(to_json(t));
        scene_reports.push_back({{"scene", scene_name},
                                 {"load", to_json(load)},
                                 {"load_milliseconds", load.milliseconds},
                                 {"frames", frames},
                                 {"render_targets", targets},
                                 {"images_held", images}});
    }
    if (auto saved = acetate_host.save_pipeline_cache(); !saved)
        std::fprintf(stderr, "acetate: warning: pipeline cache not saved: %s\n",
                     saved.error().message.c_str());

    if (command.stats) {
        // The first scene's figures stay at the top level, as for a single scene.
        nlohmann::json stats = scene_reports.front();
        stats["device"] = acetate_host.device_name();
        stats["view"] = command.view;
        stats["format"] = command.format;
        stats["scenes"] = scene_reports;
        stats["plugins_loaded"] = acetate_host.plugins_loaded();
        stats["pipelines_in_pool"] = acetate_host.pipelines_in_pool();
        stats["pipeline_cache_warning"] = acetate_host.pipeline_cache_warning();
        stats["validation_messages"] = acetate_host.validation_messages();
        if (auto written = write_file_atomically(*command.stats, stats.dump(2) + "\n"); !written)
            return fail(written.error().message);
        std::printf("stats -> %s\n", command.stats->string().c_str());
    }
    if (acetate_host.validation_messages() != 0)
        return fail(fmt::format("{} Vulkan validation messages (see above)",
                                acetate_host.validation_messages()));
    return failed_scenes ? 1 : 0;
}

}  // namespace acetate
