#include "bench_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <set>

#include "acetate/host/host.hpp"
#include "core/output_paths.hpp"
#include "plugins/plugin_loader.hpp"
#include "scene_variants.hpp"

namespace acetate::bench {
namespace {

namespace fs = std::filesystem;

std::string file_safe(std::string text) {
    for (char& ch : text)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '-') ch = '_';
    return text;
}

// The files the loader may open for `id`: <dir>/<id>.so, then <dir>/<last id segment>.so, in
// each folder of the search path (PluginLoader::load). Every one that exists counts: which one
// wins is decided only at load.
void add_plugin_files(std::vector<RunFile>& inputs, const std::vector<fs::path>& directories,
                      const std::string& id) {
    const std::string last = id.substr(id.rfind('.') + 1);
    for (const fs::path& dir : directories)
        for (const std::string& name : {id + ".so", last + ".so"}) {
            std::error_code ec;
            if (fs::is_regular_file(dir / name, ec))
                inputs.push_back({dir / name, fmt::format("plugin {}", id)});
        }
}

}  // namespace

std::string heat_map_name(size_t scene, const std::string& plugin, const std::string& preset,
                          const std::string& format) {
    return file_safe(fmt::format("heat-s{}-{}-{}-{}.png", scene, plugin, preset, format));
}

std::string chart_name(const fs::path& scene, const std::string& plugin) {
    return fmt::format("speed-error-{}-{}.svg", scene.stem().string(), plugin);
}

Result<void> check_bench_outputs(const BenchOptions& options, const std::optional<fs::path>& json,
                                 const std::optional<fs::path>& html) {
    std::vector<RunFile> inputs, outputs;
    if (json) outputs.push_back({*json, "--json"});
    if (html) outputs.push_back({*html / "index.html", "--html"});
    const std::vector<fs::path> directories =
        PluginLoader::default_directories(options.plugin_paths);
    // The presets a heat map may be named by: those asked for, "default" for a plugin that
    // declares none, and "off"; the formats: those asked for, and rgba16f for "off". Without
    // --presets, every preset a plugin declares, known only once it is loaded: then any file in
    // the folder named like one of its heat maps counts as an output.
    std::set<std::string> presets(options.presets.begin(), options.presets.end());
    presets.insert({"default", "off"});
    std::vector<std::string> heat_map_prefixes;
    std::set<std::string> formats(options.formats.begin(), options.formats.end());
    formats.insert("rgba16f");
    for (size_t s = 0; s < options.scenes.size(); ++s) {
        auto scene = parse_scene_file(options.scenes[s]);
        if (!scene) return scene.error();
        // The scene's own list of the files it reads, as `acetate render` checks it.
        auto info = host::Host::inspect_scene_file(options.scenes[s]);
        if (!info) return make_error(ErrorCode::InvalidInput, info.error().message);
        for (const host::SceneInfo::Input& input : info->inputs)
            inputs.push_back({input.file, input.field});
        for (const std::string& id : plugins_named(scene.value())) {
            add_plugin_files(inputs, directories, id);
            if (!html || (!options.plugins.empty() &&
                          std::find(options.plugins.begin(), options.plugins.end(), id) ==
                              options.plugins.end()))
                continue;
            outputs.push_back({*html / chart_name(options.scenes[s], id), "--html"});
            for (const std::string& preset : presets)
                for (const std::string& format : formats)
                    outputs.push_back({*html / heat_map_name(s, id, preset, format), "--html"});
            if (options.presets.empty())
                heat_map_prefixes.push_back(file_safe(fmt::format("heat-s{}-{}-", s, id)));
        }
    }
    std::error_code ec;
    for (const RunFile& input : inputs)
        for (const std::string& prefix : heat_map_prefixes)
            if (fs::equivalent(input.path.parent_path(), *html, ec) &&
                input.path.filename().string().rfind(prefix, 0) == 0)
                outputs.push_back({input.path, "--html"});
    return check_outputs_spare_inputs(outputs, inputs);
}

}  // namespace acetate::bench
