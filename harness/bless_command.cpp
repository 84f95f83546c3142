#include "bless_command.hpp"

#include <fmt/format.h>
#include <stdlib.h>

#include <cstdio>

#include "case_batch.hpp"
#include "core/atomic_file.hpp"
#include "references.hpp"
#include "validate.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;

int run_bless(const BlessOptions& o) {
    auto fail = [](const std::string& message) {
        std::fprintf(stderr, "acetate-harness: %s\n", message.c_str());
        return 1;
    };
    std::error_code ec;
    fs::create_directories(o.report_directory, ec);
    if (ec)
        return fail(fmt::format("{}: cannot create the report folder: {}",
                                o.report_directory.string(), ec.message()));
    // The cases run as validate runs them: validation layers on, each in its own process.
    setenv("ACETATE_VALIDATION", "1", 1);
    auto described = describe_in_child(o.self, o.plugin, o.report_directory, o.timeout_seconds);
    if (!described) return fail(described.error().message);
    auto scenes = find_reference_scenes(o.references, described->id);
    if (!scenes) return fail(scenes.error().message);
    described->reference_scenes = std::move(scenes.value());
    const PluginInfo& plugin = described.value();
    if (plugin.source_digest.empty())
        return fail(
            fmt::format("{}: bless refused: the plugin has no source digest (built "
                        "without acetate_add_effect); references bind to one",
                        plugin.id));
    const fs::path info_file = o.report_directory / "plugin.json";
    if (auto w = write_file_atomically(info_file, to_json(plugin).dump(2)); !w)
        return fail(w.error().message);

    const std::vector<CaseSpec> cases = golden_cases(plugin);
    std::printf("blessing %s %s (source %s): %zu reference cases\n", plugin.id.c_str(),
                plugin.version.c_str(), plugin.source_digest.substr(0, 12).c_str(), cases.size());
    CaseBatch run;
    run.self = o.self;
    run.plugin_info_file = info_file;
    run.report_directory = o.report_directory;
    run.jobs = o.jobs;
    run.timeout_seconds = o.timeout_seconds;
    run.total = cases.size();
    const std::vector<CaseResult> results = run_case_batch(run, cases);
    auto blessed = bless_references(o.references, plugin, cases, results, o.report_directory, o.by);
    if (!blessed) return fail(blessed.error().message);
    std::vector<ImageRGBA> images;
    for (const auto& [id, name] : blessed->images) {
        std::printf("  %-28s %s\n", id.c_str(), (blessed->directory / name).string().c_str());
        if (auto image = load_image(blessed->directory / name, ImageRole::Colour))
            images.push_back(std::move(image.value()));
    }
    const fs::path sheet = o.report_directory / "references.png";
    if (save_image(sheet, contact_sheet(images)))
        std::printf("all on one page, in that order: %s\n", sheet.string().c_str());
    std::printf(
        "%s %s: %zu reference images blessed by %s for source %s in %s; look at them before "
        "committing them: every later build of this source is judged against them\n",
        plugin.id.c_str(), plugin.version.c_str(), blessed->images.size(), o.by.c_str(),
        plugin.source_digest.substr(0, 12).c_str(), blessed->directory.string().c_str());
    return 0;
}

}  // namespace acetate::harness
