#include "check_shaders_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <regex>
#include <set>
#include <string>

#include "core/input_file.hpp"
#include "plugins/effect_graph.hpp"
#include "plugins/plugin_loader.hpp"
#include "render/effect_pipelines.hpp"
#include "render/floor_facts.hpp"
#include "scene/floor_masks.hpp"
#include "vulkan/shader_compiler.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

// A shader file is GLSL text, read once; larger than this it is not one.
constexpr size_t kMaxShaderBytes = 4 << 20;

struct ShaderFile {
    fs::path file;
    std::string text;
};

// The scene build() is told about: a 256x192 canvas of two floors, the plugin on the ground
// floor (one tile over the whole canvas carrying every mask kind the plugin reads, two point
// lights, one of them raised, and a sun), so that a plugin declares the passes it has.
SceneDesc check_scene(const EffectDescriptor& d) {
    SceneDesc scene;
    scene.file = "check-shaders";
    scene.width = 256;
    scene.height = 192;
    FloorDesc ground;
    ground.name = "ground";
    TileDesc tile;
    tile.image = "tile";
    tile.rect = {0, 0, 256, 192};
    for (const std::string& kind : d.masks) tile.masks[kind] = "mask." + kind;
    ground.tiles.push_back(tile);
    LightDesc low, raised;
    low.pos = {64, 48};
    low.radius = 80;
    raised.pos = {192, 144};
    raised.radius = 120;
    raised.height = 40;
    ground.lights = {low, raised};
    ground.sun = SunDesc{};
    scene.floors.push_back(ground);
    FloorDesc upper;
    upper.name = "upper";
    scene.floors.push_back(upper);
    return scene;
}

// The ground floor's composite of every mask kind the plugin reads: 1 over the middle of the
// canvas, 0 around it, so a plugin that reads its masks in build() (emitters, water) finds some.
FloorMasks check_masks(const EffectDescriptor& d, const SceneDesc& scene) {
    FloorMasks masks;
    for (const std::string& kind : d.masks) {
        ImageRGBA image(scene.width, scene.height);
        for (uint32_t y = 0; y < scene.height; ++y)
            for (uint32_t x = 0; x < scene.width; ++x) {
                const bool inside = x >= scene.width / 4 && x < 3 * scene.width / 4 &&
                                    y >= scene.height / 4 && y < 3 * scene.height / 4;
                std::fill_n(image.at(x, y), 4, inside ? 1.0f : 0.0f);
            }
        masks.emplace(kind, std::move(image));
    }
    return masks;
}

// Line and message of glslang's first error, "ERROR: 0:12: 'x' : undeclared identifier".
std::optional<std::pair<int, std::string>> glslang_error(const std::string& message) {
    static const std::regex pattern("ERROR: [^:]*:([0-9]+): (.*)");
    std::smatch m;
    if (!std::regex_search(message, m, pattern)) return std::nullopt;
    std::string text = m[2].str();
    text.erase(text.find_last_not_of(" \t\r") + 1);  // glslang ends some with a space
    return std::make_pair(std::stoi(m[1].str()), text);
}

size_t lines_before(const std::string& text, size_t offset) {
    return size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(offset), '\n'));
}

// Where line `line` of a pass's text is in the shader files: "tint.frag:12", or "" when the
// text is no file's (a plugin that builds its GLSL from pieces).
std::string place_in_files(const std::vector<ShaderFile>& files, const std::string& glsl,
                           int line) {
    for (const ShaderFile& f : files) {
        if (f.text.empty()) continue;
        if (const size_t at = glsl.find(f.text); at != std::string::npos) {
            const long in_file = long(line) - long(lines_before(glsl, at));
            if (in_file >= 1) return fmt::format("{}:{}", f.file.string(), in_file);
        } else if (const size_t at = f.text.find(glsl); at != std::string::npos) {
            return fmt::format("{}:{}", f.file.string(),
                               long(line) + long(lines_before(f.text, at)));
        }
    }
    return "";
}

}  // namespace

int run_check_shaders(const CheckShadersCommand& command) {
    const std::string plugin_name = command.plugin.string();
    std::vector<ShaderFile> files;
    for (const fs::path& file : command.shaders) {
        auto text = read_input_file(file, kMaxShaderBytes, "a shader");
        if (!text) {
            std::fprintf(stderr, "acetate check-shaders: %s\n", text.error().message.c_str());
            return 1;
        }
        files.push_back({file, std::move(text.value())});
    }
    PluginLoader loader({});
    auto plugin = loader.load_file(command.plugin);
    if (!plugin) {
        std::fprintf(stderr, "acetate check-shaders: %s\n", plugin.error().message.c_str());
        return 1;
    }
    const EffectDescriptor& d = (*plugin)->descriptor;
    const SceneDesc scene = check_scene(d);
    const FloorMasks masks = check_masks(d, scene);
    const bool global = d.scope == ACETATE_SCOPE_GLOBAL;
    const std::string label = fmt::format("{}.{}", global ? "global" : "floor0", d.id);

    // Each context build() is told: the defaults, then every preset.
    std::vector<std::string> presets{""};
    for (const auto& [name, values] : d.presets) presets.push_back(name);
    std::set<std::string> compiled;  // whole sources, preamble included: each compiled once
    std::set<std::string> used_files;
    size_t errors = 0, passes = 0;
    for (const std::string& preset : presets) {
        const std::string context = preset.empty() ? "defaults" : "preset \"" + preset + "\"";
        EffectRef ref{d.id, nlohmann::json::object(), preset, "check-shaders"};
        auto params = resolve_param_vectors(d, ref, plugin_name);
        if (!params) {
            std::fprintf(stderr, "%s: %s\n", plugin_name.c_str(), params.error().message.c_str());
            return 1;
        }
        FloorFacts facts;
        describe_floor(scene, global ? -1 : 0, d, params.value(),
                       ViewTransform::whole(scene.width, scene.height), facts);
        GraphContext graph_context;
        graph_context.masks = global ? nullptr : &masks;
        graph_context.canvas_width = scene.width;
        graph_context.canvas_height = scene.height;
        auto graph = build_effect_graph(**plugin, facts.info, label, graph_context);
        if (!graph) {
            std::fprintf(stderr, "%s: build() with %s: %s\n", plugin_name.c_str(), context.c_str(),
                         graph.error().message.c_str());
            ++errors;
            continue;
        }
        for (const GraphPass& pass : graph->passes) {
            if (pass.glsl.empty()) continue;  // a whole SPIR-V module: compiled by its author
            for (const ShaderFile& f : files)
                if (!f.text.empty() && (pass.glsl.find(f.text) != std::string::npos ||
                                        f.text.find(pass.glsl) != std::string::npos))
                    used_files.insert(f.file.string());
            // Plain first; the checked variant only when the plain one compiles (an error in
            // the plugin's text would be the same error twice).
            for (const bool checked : {false, true}) {
                const std::string source =
                    effect_glsl_preamble(d, pass, graph->phases, checked) + pass.glsl;
                if (!compiled.insert(source).second) continue;
                ++passes;
                const std::string pass_label = label + "." + pass.name;
                auto spirv = compile_glsl(pass_label, ShaderStage::Fragment, source);
                if (spirv) continue;
                ++errors;
                const std::string variant = checked ? ", with the harness's checked built-ins" : "";
                const auto error = glslang_error(spirv.error().message);
                const std::string place =
                    error ? place_in_files(files, pass.glsl, error->first) : std::string();
                if (!place.empty())
                    std::fprintf(stderr, "%s: error: %s (pass \"%s\", %s%s)\n", place.c_str(),
                                 error->second.c_str(), pass_label.c_str(), context.c_str(),
                                 variant.c_str());
                else
                    std::fprintf(stderr, "%s: pass \"%s\" (%s%s): %s\n", plugin_name.c_str(),
                                 pass_label.c_str(), context.c_str(), variant.c_str(),
                                 spirv.error().message.c_str());
                if (!checked) break;
            }
        }
    }
    for (const ShaderFile& f : files)
        if (!used_files.count(f.file.string()))
            std::fprintf(stderr,
                         "acetate check-shaders: warning: %s: no pass uses it with the defaults "
                         "or any preset, so it was not compiled\n",
                         f.file.string().c_str());
    if (errors) {
        std::fprintf(stderr, "acetate check-shaders: %s: %zu error%s\n", d.id.c_str(), errors,
                     errors == 1 ? "" : "s");
        return 1;
    }
    std::printf(
        "acetate check-shaders: %s: %zu pass sources compiled (plain and checked; the "
        "defaults and %zu preset%s)\n",
        d.id.c_str(), passes, presets.size() - 1, presets.size() == 2 ? "" : "s");
    return 0;
}

}  // namespace acetate
