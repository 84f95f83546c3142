#include "case_session.hpp"

#include <fmt/format.h>
#include <malloc.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <map>

#include "core/sha256.hpp"
#include "relation_checks.hpp"
#include "vulkan/pipeline_cache_file.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
// The session's renderer, on its device; `links` holds the files under test.
Result<Session> with_renderer(const CaseContext& c, const fs::path& links, Session session);
}  // namespace

// The plugin under test may have any file name; scenes name plugins by id. A private folder
// of `<id>.so` links makes the ordinary search find exactly the files under test.
Result<Session> open_session(const CaseContext& c, std::unique_ptr<VulkanContext> device) {
    const fs::path links = c.case_directory / "plugins";
    std::error_code ec;
    fs::create_directories(links, ec);
    auto link = [&](const std::string& id, const std::string& file) -> Result<void> {
        const fs::path target = links / (id + ".so");
        fs::remove(target, ec);
        fs::create_symlink(fs::absolute(file), target, ec);
        if (ec)
            return make_error(ErrorCode::Io, fmt::format("{}: cannot link the plugin: {}",
                                                         target.string(), ec.message()));
        return {};
    };
    ACETATE_TRY(link(c.plugin.id, c.plugin.file));
    for (const CompanionPlugin& other : c.spec.companions) ACETATE_TRY(link(other.id, other.file));

    Session session;
    if (device) {
        session.context = std::move(device);
        return with_renderer(c, links, std::move(session));
    }
    ContextOptions context_options = ContextOptions::from_environment();
    if (!c.spec.validation_layer) {
        // As users run their hosts: the layer must not be in the process at all, since a
        // plugin can see its library even when no context enabled it.
        context_options.validation = false;
        if (VulkanContext::validation_layer_loaded())
            return make_error(ErrorCode::InvalidInput,
                              "the case runs without the validation layer, but its library is "
                              "already loaded in this process (it was not started afresh)");
    }
    auto context = VulkanContext::create(context_options);
    if (!context) return context.error();
    session.context = std::move(context.value());
    // The layer is on for the whole process from here. The plugin is given the environment a
    // user's host gives it, without the harness's switch: a plugin that reads it could
    // otherwise behave only while it is watched.
    ::unsetenv("ACETATE_VALIDATION");
    return with_renderer(c, links, std::move(session));
}

namespace {
Result<Session> with_renderer(const CaseContext& c, const fs::path& links, Session session) {
    RendererOptions options;
    options.plugin_directories = {links};
    options.pipeline_cache_file = default_pipeline_cache_path();
    auto renderer = Renderer::create(*session.context, options);
    if (!renderer) return renderer.error();
    session.renderer = std::move(renderer.value());
    // Only the bytes the parent judged run here: the plugin under test as it was described,
    // each companion as the registry recorded it. A file rewritten or swapped since is refused
    // before its constructors run, and a case file cannot name a library of its own choosing.
    std::map<std::string, std::string> required{{c.plugin.id, c.plugin.binary_sha256}};
    for (const CompanionPlugin& other : c.spec.companions) required[other.id] = other.binary_sha256;
    session.renderer->plugins().set_admission([required](const std::string& id,
                                                         const fs::path& file,
                                                         const fs::path& contents) -> Result<void> {
        const auto wanted = required.find(id);
        if (wanted == required.end() || wanted->second.empty())
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{} ({}): not loaded: the case names no digest "
                                          "for it",
                                          id, file.string()));
        auto sha = file_sha256(contents);
        if (!sha) return sha.error();
        if (sha.value() == wanted->second) return {};
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{} ({}): not loaded: its SHA-256 {} is not the {} "
                        "judged for this run (the file changed)",
                        id, file.string(), sha->substr(0, 12), wanted->second.substr(0, 12)));
    });
    return session;
}
}  // namespace

namespace {

std::optional<std::array<float, 4>> poison_colour(Poison poison) {
    switch (poison) {
        case Poison::None:
            return std::nullopt;
        case Poison::NaN:
            return std::array<float, 4>{NAN, NAN, NAN, NAN};
        case Poison::Large:  // finite in RGBA16F, far from any colour a tile holds
            return std::array<float, 4>{49152.0f, 40960.0f, 32768.0f, 0.75f};
        case Poison::Plain:  // an ordinary colour: reading it looks plausible, but differs
            return std::array<float, 4>{0.25f, 0.5f, 0.125f, 0.5f};
    }
    return std::nullopt;
}

Result<std::unique_ptr<Compositor>> load(const CaseContext& c, Session& s, const SceneDesc& scene,
                                         const LoadOptions& how) {
    CompositorOptions options;
    options.view = OutputView::FloorRgb;  // the active floor's whole target is drawn and kept
    options.poison = poison_colour(c.spec.poison);
    options.format = c.spec.format == TargetFormat::Rgba32f ? VK_FORMAT_R32G32B32A32_SFLOAT
                                                            : VK_FORMAT_R16G16B16A16_SFLOAT;
    if (how.format) options.format = *how.format;
    options.checked_builtins = how.checked_builtins;
    options.ignore_declared_reach = how.ignore_declared_reach;
    auto comp = Compositor::load(*s.renderer, scene, options);
    if (!comp || !how.camera) return comp;
    ACETATE_TRY(comp.value()->set_view_transform(*how.camera));
    return comp;
}

}  // namespace

// ---- scenes -----------------------------------------------------------------------------

SceneEffect under_test(const CaseContext& c, json params) {
    if (params.is_null()) params = c.spec.params;
    // The harness varies a vector parameter along its diagonal: every component alike, as the
    // scene format's array.
    for (const ParamInfo& p : c.plugin.params)
        if (p.components > 1 && params.contains(p.name) && params[p.name].is_number())
            params[p.name] = json(std::vector<float>(p.components, params[p.name].get<float>()));
    return {c.plugin.id, params, c.spec.preset};
}

namespace {

// The plugin between the case's neighbours (none, unless a context case).
std::vector<SceneEffect> with_neighbours(const CaseContext& c, SceneEffect plugin) {
    std::vector<SceneEffect> effects;
    for (const std::string& id : c.spec.effects_before) effects.push_back({id});
    effects.push_back(std::move(plugin));
    for (const std::string& id : c.spec.effects_after) effects.push_back({id});
    return effects;
}

// The floor transparent (pixels and masks) within `band` pixels of the canvas's right and
// bottom edges (and its left and top ones with `all_sides`): what lies past them then reads the
// same on a larger canvas (canvas-size), or through a camera that shows more (camera-region).
void clear_canvas_edges(FloorInput& floor, uint32_t width, uint32_t height, uint32_t band,
                        bool all_sides = false) {
    if (!floor.tiled) return;
    auto clear = [&](ImageRGBA& image) {
        for (uint32_t y = 0; y < image.height; ++y)
            for (uint32_t x = 0; x < image.width; ++x) {
                const int64_t sx = int64_t(floor.x) + x, sy = int64_t(floor.y) + y;
                if (sx + band >= width || sy + band >= height ||
                    (all_sides && (sx < int64_t(band) || sy < int64_t(band))))
                    std::fill_n(image.at(x, y), 4, 0.0f);
            }
    };
    clear(floor.image);
    for (auto& [kind, mask] : floor.masks) clear(mask);
}

}  // namespace

SceneLayout case_layout(const CaseContext& c, json params) {
    const CaseSpec& s = c.spec;
    SceneLayout layout;
    layout.width = s.width;
    layout.height = s.height;
    layout.floor_effects.resize(s.floors);
    const InputChoice choice{s.pattern, s.lights, s.masks, s.floor_variant};
    for (uint32_t f = 0; f < s.floors; ++f) {
        layout.floors.push_back(
            make_floor_input(choice, s.width, s.height, f, s.floors, s.seed, c.plugin.masks));
        if (s.relation == Relation::CanvasSize || s.relation == Relation::CameraRegion)
            clear_canvas_edges(layout.floors.back(), s.width, s.height, kCanvasEdgeBand,
                               s.relation == Relation::CameraRegion);
        if (!c.plugin.is_global() && (s.plugin_floor < 0 || uint32_t(s.plugin_floor) == f))
            layout.floor_effects[f] = with_neighbours(c, under_test(c, params));
    }
    if (c.plugin.is_global()) layout.global_effects = with_neighbours(c, under_test(c, params));
    return layout;
}

// ---- captures ---------------------------------------------------------------------------

Result<ImageRGBA> render_floor(Compositor& comp, uint32_t floor, double time) {
    ACETATE_TRY(comp.render(floor, time));
    return comp.read_active_floor();
}

// What the plugin produced with floor `floor` active: that floor's target (a floor effect),
// or the composite it ran on (a global effect).
Result<ImageRGBA> plugin_output(Compositor& comp, bool global, uint32_t floor, double time) {
    if (!global) return render_floor(comp, floor, time);
    ACETATE_TRY(comp.render(floor, time));
    return comp.read_accumulation();
}

// A floor's target before and after its effects.
Result<Capture> capture_floor(Compositor& comp, uint32_t floor, double time) {
    Capture capture;
    comp.set_effects_enabled(false);
    auto input = render_floor(comp, floor, time);
    comp.set_effects_enabled(true);
    if (!input) return input.error();
    auto output = render_floor(comp, floor, time);
    if (!output) return output.error();
    capture.input = std::move(input.value());
    capture.output = std::move(output.value());
    return capture;
}

Result<Capture> capture_effect(Compositor& comp, bool global, uint32_t floor, double time,
                               uint32_t index) {
    auto run_first = [&](uint32_t count) -> Result<ImageRGBA> {
        if (global)
            comp.set_global_effects_run(count);
        else
            comp.set_floor_effects_run(count);
        return plugin_output(comp, global, floor, time);
    };
    auto input = run_first(index);
    auto output = input ? run_first(index + 1) : Result<ImageRGBA>(input.error());
    comp.set_floor_effects_run(UINT32_MAX);
    comp.set_effects_enabled(true, true);
    if (!output) return output.error();
    return Capture{std::move(input.value()), std::move(output.value())};
}

Result<Capture> capture_global_effect(Compositor& comp, uint32_t top, double time, uint32_t index) {
    return capture_effect(comp, true, top, time, index);
}

Result<Capture> capture_plugin(Compositor& comp, const CaseContext& c, uint32_t floor) {
    const bool global = c.plugin.is_global();
    const auto at = comp.effect_position(global ? std::nullopt : std::optional(floor),
                                         uint32_t(c.spec.effects_before.size()));
    if (at.runs) return capture_effect(comp, global, floor, c.spec.time, at.before);
    // Dropped at load for declaring nothing: its output is its input, after the effects before.
    if (global)
        comp.set_global_effects_run(at.before);
    else
        comp.set_floor_effects_run(at.before);
    auto input = plugin_output(comp, global, floor, c.spec.time);
    comp.set_floor_effects_run(UINT32_MAX);
    comp.set_effects_enabled(true, true);
    if (!input) return input.error();
    return Capture{input.value(), input.value()};
}

Result<ImageRGBA> plugin_own_output(Compositor& comp, const CaseContext& c, uint32_t floor) {
    auto capture = capture_plugin(comp, c, floor);
    if (!capture) return capture.error();
    return std::move(capture->output);
}

namespace {

CheckResult load_failure(const Error& error) {
    CheckResult check;
    check.check = "load";
    check.verdict = Verdict::Fail;
    check.message = error.message;
    return check;
}

}  // namespace

// ---- results ----------------------------------------------------------------------------

CaseWriter::CaseWriter(const CaseContext& c) : c_(c) {
    result.id = c.spec.id;
    result.description = c.spec.description;
    result.seed = c.spec.seed;
}

std::string CaseWriter::picture(const std::string& name, const ImageRGBA& image) {
    if (uint64_t(image.width) * image.height > 1024ull * 1024) return {};
    const fs::path file = c_.case_directory / (name + ".png");
    if (!save_image(file, image)) return {};
    return fs::relative(file, c_.report_directory).string();
}

void CaseWriter::case_picture(const std::string& role, const ImageRGBA& image) {
    if (auto path = picture(role, image); !path.empty()) result.images[role] = path;
}
void CaseWriter::add(CheckResult check, const std::map<int64_t, ImageRGBA>* heat_maps) {
    if (heat_maps)
        for (const auto& [floor, heat] : *heat_maps) {
            const std::string role =
                floor >= 0 ? fmt::format("heatmap.floor{}", floor) : "heatmap.composite";
            if (auto path = picture(check.check + "." + role, heat); !path.empty())
                check.images[role] = path;
        }
    result.checks.push_back(std::move(check));
}
void CaseWriter::add_all(std::vector<CheckResult> checks,
                         const std::map<std::string, std::map<int64_t, ImageRGBA>>& heat) {
    for (CheckResult& check : checks) {
        auto it = heat.find(check.check);
        add(std::move(check), it == heat.end() ? nullptr : &it->second);
    }
}
CaseResult CaseWriter::finish(bool validation_layer_on, uint64_t messages_before) {
    CheckResult validation;
    validation.check = "vulkan-validation";
    const uint64_t messages = VulkanContext::process_validation_message_count() - messages_before;
    if (!c_.spec.validation_layer) {
        // Run as users run their hosts; the layer's findings on these inputs come from the
        // same case with the layer (determinism/run-1).
    } else if (!validation_layer_on) {
        validation.verdict = Verdict::Skip;
        validation.message = "validation layers were off (ACETATE_VALIDATION is not 1)";
    } else if (messages) {
        validation.verdict = Verdict::Fail;
        validation.violations = messages;
        validation.message =
            fmt::format("{} validation message{} while the plugin ran (the log has them)", messages,
                        messages == 1 ? "" : "s");
    } else {
        validation.message = "no validation message while the plugin ran";
    }
    if (c_.spec.validation_layer) result.checks.push_back(validation);
    for (const CheckResult& check : result.checks)
        result.verdict = std::max(result.verdict, check.verdict);
    return result;
}

std::vector<uint32_t> plugin_floors(const CaseContext& c) {
    std::vector<uint32_t> floors;
    if (c.plugin.is_global()) return floors;
    for (uint32_t f = 0; f < c.spec.floors; ++f)
        if (c.spec.plugin_floor < 0 || uint32_t(c.spec.plugin_floor) == f) floors.push_back(f);
    return floors;
}

Result<bool> render_history(const CaseContext& c, Session& s, CaseWriter& w) {
    // Other canvases (odd and even, smaller and larger) and other floor counts than the case's,
    // so that state sized or indexed by the first load shows.
    for (uint32_t i = 0; i < c.spec.prior_loads; ++i) {
        CaseContext other = c;
        other.spec.width = i % 2 ? c.spec.width + 33 : std::max(1u, c.spec.width / 2 + 1);
        other.spec.height = i % 2 ? c.spec.height / 2 + 1 : c.spec.height + 17;
        other.spec.floors = i % 2 ? 1 : c.spec.floors + 1;
        other.spec.plugin_floor = -1;
        other.spec.seed = c.spec.seed + 1 + i;
        auto comp = load_layout(other, s, w, case_layout(other), fmt::format("prior{}", i));
        if (!comp) return comp.error();
        if (!*comp) return false;
        for (uint32_t f = 0; f < other.spec.floors; ++f)
            ACETATE_TRY((**comp).render(f, c.spec.time + 0.5f * float(f + 1)));
    }
    return true;
}

Result<void> render_earlier_frames(Compositor& comp, const CaseContext& c) {
    const uint32_t floors = c.spec.floors;
    for (uint32_t i = 1; i < c.spec.frames; ++i)
        ACETATE_TRY(comp.render(i % floors, c.spec.time - float(c.spec.frames - i) / 30.0f));
    return {};
}

uint64_t resident_bytes() {
    // Free memory the allocator keeps goes back to the system first, so only memory in use
    // counts: glibc serving a megabyte-sized allocation from the heap after a free (its mmap
    // threshold adapts) and keeping the heap's top is not a leak, and made the growth swing by
    // 0 to 2 MB between identical runs. A leak is in use, so it still counts in full.
    malloc_trim(0);
    std::ifstream statm("/proc/self/statm");
    uint64_t size = 0, resident = 0;
    statm >> size >> resident;
    return resident * uint64_t(sysconf(_SC_PAGESIZE));
}

Result<std::unique_ptr<Compositor>> load_layout(const CaseContext& c, Session& s, CaseWriter& w,
                                                const SceneLayout& layout, const std::string& name,
                                                const LoadOptions& how) {
    auto scene = write_scene(layout, c.case_directory, name);
    if (!scene) return scene.error();
    return load_scene(c, s, w, scene.value(), how);
}

Result<std::unique_ptr<Compositor>> load_scene(const CaseContext& c, Session& s, CaseWriter& w,
                                               const SceneDesc& scene, const LoadOptions& how) {
    auto comp = load(c, s, scene, how);
    if (!comp) {
        w.add(load_failure(comp.error()));
        return std::unique_ptr<Compositor>();
    }
    return comp;
}

}  // namespace acetate::harness
