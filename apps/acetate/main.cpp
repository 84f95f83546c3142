// The `acetate` command line. Subcommands and flags are binding: other tools call them.

#include <CLI/CLI.hpp>
#include <cstdio>

#include "../flag_values.hpp"
#include "check_shaders_command.hpp"
#include "core/number_text.hpp"
#include "render_command.hpp"
#include "time_list.hpp"

int main(int argc, char** argv) {
    CLI::App app{"Acetate: a headless Vulkan compositor for layered 2D scenes"};
    app.require_subcommand(1);

    acetate::RenderCommand render;
    std::string floors_list;
    CLI::App* cmd = app.add_subcommand("render", "Render a scene to an image");
    cmd->add_option("scenes", render.scenes,
                    "Scene files (acetate-scene/1 JSON), rendered in turn in one process")
        ->required();
    cmd->add_option("-o,--output", render.output,
                    "Output image: .exr (half, premultiplied, "
                    "linear) or .png (8-bit sRGB, straight alpha)")
        ->required();
    // Numbers go through the one reader (apps/flag_values.hpp): finite, in range, no wrap.
    auto* floor = acetate::flags::add_number(cmd, "--floor", render.floor, 0, UINT32_MAX,
                                             "Active floor (default: the scene's)");
    cmd->add_option("--floors", floors_list,
                    "Active floors to render in turn in one process, e.g. 0,1,2,1, or \"all\" "
                    "(every floor of each scene, bottom to top); writes OUT with the floor "
                    "index before the extension")
        ->excludes(floor);
    cmd->add_option("--view", render.view,
                    "normal | floor-alpha | accum-alpha | floor-rgb | violations | isolation")
        ->default_val("normal");
    cmd->add_option("--format", render.format, "Render target format: rgba16f | rgba32f")
        ->default_val("rgba16f");
    cmd->add_option("--stats", render.stats, "Write load and per-frame statistics as JSON");
    cmd->add_option("--plugin-path", render.plugin_paths,
                    "Directory to search for effect plugins first (repeatable); then "
                    "ACETATE_PLUGIN_PATH, then the installation's lib/acetate/plugins");
    auto* time = acetate::flags::add_number(
        cmd, "--time", render.time, -acetate::flags::kMaxTimeSeconds,
        acetate::flags::kMaxTimeSeconds, "Time in seconds that effects animate with");
    std::string times_list;
    cmd->add_option(
           "--times", times_list,
           "Times to render each floor at in one process: a list (0,0.5,2) or "
           "START:END:STEP with the end included, each S or N/D (0:11/12:1/12); writes OUT with "
           ".frameNNNN (the time's index) before the extension")
        ->excludes(time);
    std::vector<std::string> param_texts, preset_texts;
    cmd->add_option("--param", param_texts,
                    "FLOOR.EFFECT.NAME=VALUE (repeatable): an effect's parameter for this run, as "
                    "if the scene said so; FLOOR a floor's name or index or \"global\", EFFECT "
                    "a plugin id or the entry's index, VALUE a number or 2-3 joined by commas");
    cmd->add_option("--preset", preset_texts,
                    "FLOOR.EFFECT=PRESET (repeatable): an effect's preset for this run");
    cmd->add_flag("!--no-pipeline-cache", render.pipeline_cache,
                  "Do not read or write the pipeline cache in the user cache directory");
    cmd->add_option("--registry", render.registry,
                    "Validation registry that decides which plugins load (default: "
                    "ACETATE_REGISTRY, else the build tree's validation/registry.json, or "
                    "$XDG_DATA_HOME/acetate/registry.json when installed)");
    cmd->add_option("--allowed-signers", render.allowed_signers,
                    "The maintainers' keys that verify the registry's sign-offs (default: "
                    "ACETATE_ALLOWED_SIGNERS, else validation/allowed_signers)");
    cmd->add_flag("--allow-unvalidated", render.allow_unvalidated,
                  "Load plugins the registry does not have VALIDATED for their exact binary, "
                  "with a warning");

    acetate::CheckShadersCommand check;
    CLI::App* check_cmd = app.add_subcommand(
        "check-shaders",
        "Compile every GLSL pass a plugin declares, with the host's preamble (acetate_add_effect "
        "runs it at build time)");
    check_cmd->add_option("plugin", check.plugin, "The plugin library (.so)")->required();
    check_cmd->add_option("--shader", check.shaders,
                          "A GLSL file the passes' text comes from (repeatable): errors then "
                          "name it and its line");

    try {
        app.parse(argc, argv);
        if (cmd->count("--times") > 0) {
            auto times = acetate::parse_render_times(times_list, acetate::flags::kMaxTimeSeconds);
            if (!times) throw CLI::ValidationError(times.error().message);
            render.times = std::move(times.value());
        }
        for (const std::string& text : param_texts) {
            auto flag = acetate::parse_param_flag(text, false);
            if (!flag) throw CLI::ValidationError(flag.error().message);
            render.params.push_back(std::move(flag.value()));
        }
        for (const std::string& text : preset_texts) {
            auto flag = acetate::parse_param_flag(text, true);
            if (!flag) throw CLI::ValidationError(flag.error().message);
            render.params.push_back(std::move(flag.value()));
        }
        if (floors_list == "all") {
            render.all_floors = true;
        } else if (cmd->count("--floors") > 0) {
            size_t start = 0;
            while (start <= floors_list.size()) {
                const size_t comma = floors_list.find(',', start);
                const std::string item = floors_list.substr(start, comma - start);
                auto value = acetate::number_text::read<uint32_t>(item, "--floors");
                if (!value) throw std::invalid_argument(item);
                render.floors.push_back(value.value());
                if (comma == std::string::npos) break;
                start = comma + 1;
            }
        }
    } catch (const CLI::ValidationError& e) {
        // A value a flag refuses: the reader's one line, without CLI11's second.
        std::fprintf(stderr, "acetate: %s\n", e.what());
        return 2;
    } catch (const CLI::ParseError& e) {
        // --help exits 0; every usage error exits 2 (docs/conventions.md, exit codes).
        return app.exit(e) == 0 ? 0 : 2;
    } catch (const std::exception&) {
        std::fprintf(
            stderr,
            "acetate: --floors: expected floor indices like 0,1,2,1 or \"all\", got \"%s\"\n",
            floors_list.c_str());
        return 2;
    }
    try {
        if (check_cmd->parsed()) return acetate::run_check_shaders(check);
        return acetate::run_render(render);
    } catch (const std::exception& e) {
        // Out of memory and the like: still one line and a non-zero exit, never an abort.
        std::fprintf(stderr, "acetate: %s\n", e.what());
        return 1;
    }
}
