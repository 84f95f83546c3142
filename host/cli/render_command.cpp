#include "cli/render_command.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cstdio>

#include "core/atomic_file.hpp"
#include "render/compositor.hpp"
#include "scene/image_io.hpp"
#include "scene/scene.hpp"
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

// Effects arrive with the plugin runtime; until then a scene that names one is refused rather
// than rendered without it.
Result<void> refuse_effects(const SceneDesc& scene) {
    std::vector<const EffectRef*> refs;
    for (const FloorDesc& f : scene.floors)
        for (const EffectRef& e : f.effects) refs.push_back(&e);
    for (const EffectRef& e : scene.global_effects) refs.push_back(&e);
    if (refs.empty()) return {};
    return make_error(ErrorCode::InvalidInput,
                      fmt::format("{}: {}.plugin: cannot load plugin \"{}\": this build has no "
                                  "plugin runtime yet",
                                  scene.file.string(), refs.front()->where, refs.front()->plugin));
}

}  // namespace

std::filesystem::path frame_output_path(const std::filesystem::path& output, uint32_t floor,
                                        bool several) {
    if (!several) return output;
    std::filesystem::path p = output;
    p.replace_filename(fmt::format("{}.floor{}{}", output.stem().string(), floor,
                                   output.extension().string()));
    return p;
}

int run_render(const RenderCommand& command) {
    std::string ext = command.output.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".exr" && ext != ".png")
        return fail(fmt::format("-o {}: the output must end in .exr or .png",
                                command.output.string()));
    auto view = parse_view(command.view);
    if (!view) return fail(view.error());
    CompositorOptions options;
    options.view = view.value();
    if (command.format == "rgba16f") options.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    else if (command.format == "rgba32f") options.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    else return fail(fmt::format("--format: expected rgba16f or rgba32f, got \"{}\"", command.format));

    auto scene = parse_scene_file(command.scene);
    if (!scene) return fail(scene.error());
    if (auto refused = refuse_effects(scene.value()); !refused) return fail(refused.error());

    std::vector<uint32_t> floors = command.floors;
    if (floors.empty()) floors.push_back(command.floor.value_or(scene->active_floor));
    for (uint32_t f : floors)
        if (f >= scene->floors.size())
            return fail(fmt::format("{}: floor {} does not exist (the scene has floors 0..{})",
                                    command.floors.empty() ? "--floor" : "--floors", f,
                                    scene->floors.size() - 1));

    auto context = VulkanContext::create(ContextOptions::from_environment());
    if (!context) return fail(context.error());
    std::printf("device: %s\n", (*context)->device_name().c_str());

    auto compositor = Compositor::load(*context.value(), scene.value(), options);
    if (!compositor) return fail(compositor.error());
    const LoadStats& load = (*compositor)->load_stats();
    std::printf("loaded %s in %.1f ms: %llu images, %llu targets, %llu shaders, %llu pipelines\n",
                command.scene.string().c_str(), load.milliseconds,
                (unsigned long long)load.images_loaded, (unsigned long long)load.targets_allocated,
                (unsigned long long)load.shaders_compiled,
                (unsigned long long)load.pipelines_created);

    if (load.tile_texel_violations)
        std::fprintf(stderr,
                     "acetate: warning: %s: %llu tile texels have colour at alpha 0 (or NaN/Inf); "
                     "they are dropped\n",
                     command.scene.string().c_str(), (unsigned long long)load.tile_texel_violations);
    nlohmann::json frames = nlohmann::json::array();
    const bool several = floors.size() > 1;
    for (size_t i = 0; i < floors.size(); ++i) {
        auto stats = (*compositor)->render(floors[i]);
        if (!stats) return fail(stats.error());
        auto pixels = (*compositor)->read_output();
        if (!pixels) return fail(pixels.error());
        const auto path = frame_output_path(command.output, floors[i], several);
        if (auto saved = save_image(path, pixels.value()); !saved) return fail(saved.error());
        std::printf("[%zu/%zu] floor %u: %.2f ms, %u passes, %llu pixels shaded, %llu violations "
                    "-> %s\n",
                    i + 1, floors.size(), floors[i], stats->milliseconds, stats->passes,
                    (unsigned long long)stats->pixels_shaded,
                    (unsigned long long)stats->violations, path.string().c_str());
        frames.push_back(to_json(stats.value()));
    }

    if (command.stats) {
        nlohmann::json targets = nlohmann::json::array();
        for (const TargetInfo& t : (*compositor)->targets_held()) targets.push_back(to_json(t));
        nlohmann::json images = nlohmann::json::array();
        for (const TargetInfo& t : (*compositor)->images_held()) images.push_back(to_json(t));
        const nlohmann::json stats = {{"device", (*context)->device_name()},
                                      {"scene", command.scene.string()},
                                      {"view", command.view},
                                      {"format", command.format},
                                      {"load", to_json(load)},
                                      {"load_milliseconds", load.milliseconds},
                                      {"frames", frames},
                                      {"render_targets", targets},
                                      {"images_held", images},
                                      {"validation_messages",
                                       (*context)->validation_messages().size()}};
        if (auto written = write_file_atomically(*command.stats, stats.dump(2) + "\n"); !written)
            return fail(written.error());
        std::printf("stats -> %s\n", command.stats->string().c_str());
    }
    if (!(*context)->validation_messages().empty())
        return fail(fmt::format("{} Vulkan validation messages (see above)",
                                (*context)->validation_messages().size()));
    return 0;
}

}  // namespace acetate
