#include "bench_runner.hpp"

#include <fmt/format.h>
#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>

#include "bench_outputs.hpp"
#include "config_measure.hpp"
#include "image_compare.hpp"
#include "peer_flatten.hpp"
#include "render/renderer.hpp"
#include "scene_variants.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::bench {
namespace {

namespace fs = std::filesystem;

std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    in >> a >> b >> c;
    return a.empty() ? "unknown" : a + " " + b + " " + c;
}

// One plugin of one scene: the presets the bench runs it at, and its reference preset.
struct PluginPlan {
    std::string id;
    std::vector<std::string> presets;  // "" stands for "no preset" (the plugin declares none)
    std::string reference_preset;
};

Result<PluginPlan> plan_plugin(Renderer& renderer, const std::string& id,
                               const BenchOptions& options) {
    auto plugin = renderer.plugins().load(id);
    if (!plugin) return plugin.error();
    const auto& declared = plugin.value()->descriptor.presets;
    PluginPlan plan{id, {}, ""};
    if (declared.empty()) {  // nothing to choose: the formats alone, against rgba32f
        plan.presets = {""};
        return plan;
    }
    const auto& order = plugin.value()->descriptor.preset_order;
    for (const std::string& preset : options.presets.empty() ? order : options.presets) {
        if (!declared.count(preset)) {
            std::string names;
            for (const auto& [name, values] : declared) names += (names.empty() ? "" : ", ") + name;
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("--presets: plugin {} has no preset \"{}\" (it has {})",
                                          id, preset, names));
        }
        plan.presets.push_back(preset);
    }
    // Error is measured against the best the plugin can do: "ultra", or else its last preset
    // (presets are declared cheapest first).
    plan.reference_preset = declared.count("ultra") ? "ultra" : order.back();
    return plan;
}

std::string preset_label(const std::string& preset) {
    return preset.empty() ? "default" : preset;
}

}  // namespace

Result<void> BenchDevice::check_validation() const {
    if (context->validation_messages().empty()) return {};
    return make_error(ErrorCode::VulkanCall,
                      fmt::format("Vulkan validation: {}", context->validation_messages().front()));
}

Result<BenchDevice> open_device(const std::vector<std::filesystem::path>& plugin_paths) {
    auto context = VulkanContext::create(ContextOptions::from_environment());
    if (!context) return context.error();
    RendererOptions renderer_options;
    renderer_options.plugin_directories = PluginLoader::default_directories(plugin_paths);
    auto renderer = Renderer::create(*context.value(), renderer_options);
    if (!renderer) return renderer.error();
    return BenchDevice{std::move(context.value()), std::move(renderer.value())};
}

Result<BenchResults> run_bench(const BenchOptions& options, const ProgressFn& progress) {
    for (const std::string& f : options.formats)
        if (parse_format(f) == VK_FORMAT_UNDEFINED)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("--formats: expected rgba16f or rgba32f, got \"{}\"", f));
    // Every scene is parsed before the device starts: bad input fails fast.
    std::vector<SceneDesc> scenes;
    for (const fs::path& file : options.scenes) {
        auto scene = parse_scene_file(file);
        if (!scene) return scene.error();
        const uint32_t floor = options.floor.value_or(scene->active_floor);
        if (floor >= scene->floors.size())
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("--floor: floor {} does not exist in {} (floors 0..{})",
                                          floor, file.string(), scene->floors.size() - 1));
        scenes.push_back(std::move(scene.value()));
    }
    for (const std::string& id : options.plugins)
        if (std::none_of(scenes.begin(), scenes.end(),
                         [&](const SceneDesc& s) { return plugins_named(s).count(id); }))
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("--plugins: no scene names the plugin {}", id));

    auto device = open_device(options.plugin_paths);
    if (!device) return device.error();
    auto& renderer = device->renderer;

    BenchResults results;
    results.device = device->context->device_name();
    results.date = utc_now();
    results.load = load_average();
    results.frames = options.frames;
    results.thresholds = options.thresholds;

    // The whole plan first, so the progress line can say "[k/n]".
    struct Job {
        size_t scene;
        PluginPlan plugin;
    };
    std::vector<Job> jobs;
    size_t total = 0;
    for (size_t s = 0; s < scenes.size(); ++s)
        for (const std::string& id : plugins_named(scenes[s])) {
            if (!options.plugins.empty() &&
                std::find(options.plugins.begin(), options.plugins.end(), id) ==
                    options.plugins.end())
                continue;
            auto plan = plan_plugin(*renderer, id, options);
            if (!plan) return plan.error();
            // The reference, the grid (which may hold the reference: measured once), "off".
            const bool grid_has_reference =
                std::count(plan->presets.begin(), plan->presets.end(), plan->reference_preset) &&
                std::count(options.formats.begin(), options.formats.end(), "rgba32f");
            total += 2 + plan->presets.size() * options.formats.size() - grid_has_reference;
            jobs.push_back({s, std::move(plan.value())});
        }
    // The limits first: the first frame after a load must meet only what that load compiled.
    for (const SceneDesc& scene : scenes) {
        progress(
            fmt::format("{}: the frame against its limits (first frame, floor switch, "
                        "pixels shaded against the minimum)",
                        scene.file.filename().string()));
        auto limits = measure_limits(*renderer, scene, options.floor.value_or(scene.active_floor),
                                     options.frames, options.time);
        if (!limits) return limits.error();
        results.limits.push_back(limits.value());
    }

    size_t done = 0;
    auto run = [&](const SceneDesc& scene, const std::string& plugin, const std::string& preset,
                   const std::string& format) -> Result<Measurement> {
        progress(fmt::format("[{}/{}] {} {} {} {}: load, first frame, {} frames", ++done, total,
                             scene.file.filename().string(), plugin, preset_label(preset), format,
                             options.frames));
        const uint32_t floor = options.floor.value_or(scene.active_floor);
        auto m = measure_config(*renderer, scene, parse_format(format), floor, options.frames,
                                options.time);
        if (!m) return m.error();
        m->result.scene = scene.file.string();
        m->result.plugin = plugin;
        m->result.preset = preset_label(preset);
        m->result.format = format;
        // Pass labels read "floor2.acetate.water.shade" / "global.acetate.bloom.up1".
        for (const PassTime& p : m->result.gpu_passes)
            if (p.name.find("." + plugin + ".") != std::string::npos)
                m->result.effect_gpu_ms += p.milliseconds;
        return m;
    };

    for (const Job& job : jobs) {
        const SceneDesc& scene = scenes[job.scene];
        const std::string& id = job.plugin.id;
        auto reference = run(with_preset(scene, id, job.plugin.reference_preset), id,
                             job.plugin.reference_preset, "rgba32f");
        if (!reference) return reference.error();
        reference->result.reference = true;
        auto errors = compare_images(reference->image, reference->image, options.thresholds);
        if (!errors) return errors.error();
        reference->result.error = errors.value();
        results.configs.push_back(reference->result);

        auto record = [&](Measurement& m) -> Result<void> {
            ImageRGBA heat;
            auto e = compare_images(m.image, reference->image, options.thresholds,
                                    options.heat_map_dir ? &heat : nullptr);
            if (!e) return e.error();
            m.result.error = e.value();
            if (options.heat_map_dir) {
                m.result.heat_map = heat_map_name(job.scene, id, m.result.preset, m.result.format);
                ACETATE_TRY(save_image(*options.heat_map_dir / m.result.heat_map, heat));
            }
            results.configs.push_back(m.result);
            return {};
        };
        for (const std::string& preset : job.plugin.presets)
            for (const std::string& format : options.formats) {
                // The reference is in the results already, compared with itself.
                if (preset == job.plugin.reference_preset && format == "rgba32f") continue;
                auto m = run(with_preset(scene, id, preset), id, preset, format);
                if (!m) return m.error();
                ACETATE_TRY(record(m.value()));
            }
        auto off = run(without_plugin(scene, id), id, "off", "rgba16f");
        if (!off) return off.error();
        ACETATE_TRY(record(off.value()));
    }

    if (options.peers)
        for (const SceneDesc& scene : scenes) {
            progress(
                fmt::format("{}: the same flattening by oiiotool, and by acetate without "
                            "effects",
                            scene.file.filename().string()));
            const SceneDesc flat = without_effects(scene);
            auto m = measure_config(*renderer, flat, VK_FORMAT_R16G16B16A16_SFLOAT,
                                    uint32_t(flat.floors.size() - 1), options.frames, 0.0);
            if (!m) return m.error();
            std::string folder = (fs::temp_directory_path() / "acetate-bench-XXXXXX").string();
            if (!mkdtemp(folder.data()))
                return make_error(ErrorCode::Io,
                                  fmt::format("{}: cannot create a temporary folder", folder));
            const fs::path work = folder;
            const auto save_start = std::chrono::steady_clock::now();
            ACETATE_TRY(save_image(work / "acetate-flattened.exr", m->image));
            const double save_ms = std::chrono::duration<double, std::milli>(
                                       std::chrono::steady_clock::now() - save_start)
                                       .count();
            AcetateFlattening acetate;
            // What oiiotool's run does too: read the tiles, flatten, fetch, write the EXR.
            acetate.run_ms =
                m->result.load_ms + m->result.first_frame_ms + m->readback_ms + save_ms;
            acetate.frame_ms = m->result.median_ms;
            acetate.image = std::move(m->image);
            auto peer = flatten_with_oiiotool(flat, acetate, work, options.thresholds);
            std::error_code ec;
            fs::remove_all(work, ec);
            if (!peer) return peer.error();
            results.peers.push_back(peer.value());
        }

    ACETATE_TRY(device->check_validation());
    return results;
}

}  // namespace acetate::bench
