#include "case_runner.hpp"

#include <Imath/half.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

#include "contract_checks.hpp"
#include "render/compositor.hpp"
#include "render/renderer.hpp"
#include "synthetic_inputs.hpp"
#include "vulkan/pipeline_cache_file.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// ---- the GPU session: one device, one renderer, the plugins found by id ------------------

struct Session {
    std::unique_ptr<VulkanContext> context;
    std::unique_ptr<Renderer> renderer;
};

// The plugin under test may have any file name; scenes name plugins by id. A private folder
// of `<id>.so` links makes the ordinary search find exactly the files under test.
Result<Session> open_session(const CaseContext& c) {
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
    auto context = VulkanContext::create(ContextOptions::from_environment());
    if (!context) return context.error();
    session.context = std::move(context.value());
    RendererOptions options;
    options.plugin_directories = {links};
    options.pipeline_cache_file = default_pipeline_cache_path();
    auto renderer = Renderer::create(*session.context, options);
    if (!renderer) return renderer.error();
    session.renderer = std::move(renderer.value());
    return session;
}

Result<std::unique_ptr<Compositor>> load(Session& s, const SceneDesc& scene) {
    CompositorOptions options;
    options.view = OutputView::FloorRgb;  // the active floor's whole target is drawn and kept
    return Compositor::load(*s.renderer, scene, options);
}

// ---- scenes -----------------------------------------------------------------------------

SceneEffect under_test(const CaseContext& c, json params = nullptr) {
    return {c.plugin.id, params.is_null() ? c.spec.params : params, c.spec.preset};
}

// Every floor carries the plugin (a floor effect) or the composite does (a global one).
SceneLayout plugin_everywhere(const CaseContext& c, json params = nullptr) {
    const CaseSpec& s = c.spec;
    SceneLayout layout;
    layout.width = s.width;
    layout.height = s.height;
    layout.floor_effects.resize(s.floors);
    for (uint32_t f = 0; f < s.floors; ++f) {
        layout.floors.push_back(
            make_floor_input(s.pattern, s.width, s.height, f, s.floors, s.seed, c.plugin.masks));
        if (!c.plugin.is_global()) layout.floor_effects[f].push_back(under_test(c, params));
    }
    if (c.plugin.is_global()) layout.global_effects.push_back(under_test(c, params));
    return layout;
}

// ---- captures ---------------------------------------------------------------------------

struct Capture {
    ImageRGBA input, output;
};

Result<ImageRGBA> render_floor(Compositor& comp, uint32_t floor, float time) {
    ACETATE_TRY(comp.render(floor, time));
    return comp.read_active_floor();
}

// What the plugin produced with floor `floor` active: that floor's target (a floor effect),
// or the composite it ran on (a global effect).
Result<ImageRGBA> plugin_output(Compositor& comp, bool global, uint32_t floor, float time) {
    if (!global) return render_floor(comp, floor, time);
    ACETATE_TRY(comp.render(floor, time));
    return comp.read_accumulation();
}

// A floor's target before and after its effects.
Result<Capture> capture_floor(Compositor& comp, uint32_t floor, float time) {
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

// The composite of floors 0..top before and after the global effects.
Result<Capture> capture_global(Compositor& comp, uint32_t top, float time) {
    Capture capture;
    comp.set_effects_enabled(true, false);
    auto before = comp.render(top, time);
    auto input = before ? comp.read_accumulation() : Result<ImageRGBA>(before.error());
    comp.set_effects_enabled(true, true);
    if (!input) return input.error();
    ACETATE_TRY(comp.render(top, time));
    auto output = comp.read_accumulation();
    if (!output) return output.error();
    capture.input = std::move(input.value());
    capture.output = std::move(output.value());
    return capture;
}

// ---- results ----------------------------------------------------------------------------

class CaseWriter {
  public:
    explicit CaseWriter(const CaseContext& c) : c_(c) {
        result.id = c.spec.id;
        result.description = c.spec.description;
        result.seed = c.spec.seed;
    }

    // Saves a picture for the report (small enough to look at), returning its relative path.
    std::string picture(const std::string& name, const ImageRGBA& image) {
        if (uint64_t(image.width) * image.height > 1024ull * 1024) return {};
        const fs::path file = c_.case_directory / (name + ".png");
        if (!save_image(file, image)) return {};
        return fs::relative(file, c_.report_directory).string();
    }
    void case_picture(const std::string& role, const ImageRGBA& image) {
        if (auto path = picture(role, image); !path.empty()) result.images[role] = path;
    }
    void add(CheckResult check, const std::map<int64_t, ImageRGBA>* heat_maps = nullptr) {
        if (heat_maps)
            for (const auto& [floor, heat] : *heat_maps) {
                const std::string role =
                    floor >= 0 ? fmt::format("heatmap.floor{}", floor) : "heatmap.composite";
                if (auto path = picture(check.check + "." + role, heat); !path.empty())
                    check.images[role] = path;
            }
        result.checks.push_back(std::move(check));
    }
    void add_all(std::vector<CheckResult> checks,
                 const std::map<std::string, std::map<int64_t, ImageRGBA>>& heat) {
        for (CheckResult& check : checks) {
            auto it = heat.find(check.check);
            add(std::move(check), it == heat.end() ? nullptr : &it->second);
        }
    }
    CaseResult finish() {
        CheckResult validation;
        validation.check = "vulkan-validation";
        const uint64_t messages = VulkanContext::process_validation_message_count();
        const bool enabled = std::getenv("ACETATE_VALIDATION") &&
                             std::string(std::getenv("ACETATE_VALIDATION")) == "1";
        if (!enabled) {
            validation.verdict = Verdict::Skip;
            validation.message = "validation layers were off (ACETATE_VALIDATION is not 1)";
        } else if (messages) {
            validation.verdict = Verdict::Fail;
            validation.violations = messages;
            validation.message =
                fmt::format("{} validation message{} while the plugin ran (the log has them)",
                            messages, messages == 1 ? "" : "s");
        } else {
            validation.message = "no validation message while the plugin ran";
        }
        result.checks.push_back(validation);
        for (const CheckResult& check : result.checks)
            result.verdict = std::max(result.verdict, check.verdict);
        return result;
    }
    CaseResult result;

  private:
    const CaseContext& c_;
};

CheckResult load_failure(const Error& error) {
    CheckResult check;
    check.check = "load";
    check.verdict = Verdict::Fail;
    check.message = error.message;
    return check;
}

uint64_t resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    uint64_t size = 0, resident = 0;
    statm >> size >> resident;
    return resident * uint64_t(sysconf(_SC_PAGESIZE));
}

// Writes the layout's scene and loads it. A scene the host refuses (the plugin's build()
// failed, a shader did not compile) is the case's "load" failure: it is recorded and the
// result is null, so the case stops there. Environment failures come back as errors.
Result<std::unique_ptr<Compositor>> load_layout(const CaseContext& c, Session& s, CaseWriter& w,
                                                const SceneLayout& layout,
                                                const std::string& name) {
    auto scene = write_scene(layout, c.case_directory, name);
    if (!scene) return scene.error();
    auto comp = load(s, scene.value());
    if (!comp) {
        w.add(load_failure(comp.error()));
        return std::unique_ptr<Compositor>();
    }
    return comp;
}

// ---- the kinds --------------------------------------------------------------------------

// Renders the plugin's floors (or the composite) and checks each against its input.
Result<void> run_contract(const CaseContext& c, Session& s, CaseWriter& w) {
    auto comp = load_layout(c, s, w, plugin_everywhere(c), "scene");
    if (!comp) return comp.error();
    if (!*comp) return {};
    std::vector<Capture> captures;
    std::vector<FloorImages> floors;
    if (c.plugin.is_global()) {
        auto capture = capture_global(**comp, c.spec.floors - 1, c.spec.time);
        if (!capture) return capture.error();
        captures.push_back(std::move(capture.value()));
    } else {
        for (uint32_t f = 0; f < c.spec.floors; ++f) {
            auto capture = capture_floor(**comp, f, c.spec.time);
            if (!capture) return capture.error();
            captures.push_back(std::move(capture.value()));
        }
    }
    for (size_t i = 0; i < captures.size(); ++i) {
        const int64_t floor = c.plugin.is_global() ? -1 : int64_t(i);
        floors.push_back({floor, &captures[i].input, &captures[i].output});
        const std::string suffix = floor >= 0 ? fmt::format("floor{}", floor) : "composite";
        w.case_picture("input." + suffix, captures[i].input);
        w.case_picture("output." + suffix, captures[i].output);
    }
    // NaN/Inf anywhere: the composite of every floor with all effects on, too.
    ACETATE_TRY((**comp).render(c.spec.floors - 1, c.spec.time));
    auto composite = (**comp).read_accumulation();
    if (!composite) return composite.error();
    w.case_picture("composite", *composite);
    std::map<std::string, std::map<int64_t, ImageRGBA>> heat;
    w.add_all(
        check_contract(floors, c.plugin.is_expanding(), &heat, {{-1, nullptr, &composite.value()}}),
        heat);
    return {};
}

// Two frames of each floor must match bit for bit; the digest lets the parent compare two
// processes. The outputs are kept as EXR so the parent can show where they differ.
Result<void> run_determinism(const CaseContext& c, Session& s, CaseWriter& w) {
    auto comp = load_layout(c, s, w, plugin_everywhere(c), "scene");
    if (!comp) return comp.error();
    if (!*comp) return {};
    const bool global = c.plugin.is_global();
    std::vector<ImageRGBA> outputs;
    CheckAccumulator frames("determinism",
                            global ? "two frames of the composite matched bit for bit, with "
                                     "each floor active"
                                   : "two frames of every floor matched bit for bit");
    for (uint32_t f = 0; f < c.spec.floors; ++f) {
        auto first = plugin_output(**comp, global, f, c.spec.time);
        if (!first) return first.error();
        auto second = plugin_output(**comp, global, f, c.spec.time);
        if (!second) return second.error();
        record_differences(*first, *second, global ? -1 : int64_t(f), "the second frame differs",
                           frames);
        outputs.push_back(std::move(first.value()));
        // Kept so the parent can show where two processes differ (output.floorN: with floor N
        // active, whichever image the plugin wrote).
        if (!save_image(c.case_directory / fmt::format("output.floor{}.exr", f), outputs.back()))
            return make_error(ErrorCode::Io, "cannot write the determinism outputs");
    }
    auto composite = (**comp).read_accumulation();
    if (!composite) return composite.error();
    outputs.push_back(std::move(composite.value()));
    std::vector<const ImageRGBA*> all;
    for (const ImageRGBA& image : outputs) all.push_back(&image);
    w.result.output_digest = digest_images(all);
    w.case_picture("output.composite", outputs.back());
    w.add(frames.finish());
    return {};
}

// Floors 0, 1, 0 in one load; each floor alone; a second load; memory over many switches.
Result<void> run_state_isolation(const CaseContext& c, Session& s, CaseWriter& w) {
    const SceneLayout layout = plugin_everywhere(c);
    auto comp = load_layout(c, s, w, layout, "scene");
    if (!comp) return comp.error();
    if (!*comp) return {};
    const bool global = c.plugin.is_global();
    auto frame = [&](Compositor& compositor, uint32_t k) {
        return plugin_output(compositor, global, k, c.spec.time);
    };
    CheckAccumulator state("state-isolation",
                           "floors 0, 1, 0 gave floor 0 twice the same; each floor alone and a "
                           "second load gave the same images");
    auto expect_same = [&](const ImageRGBA& a, const ImageRGBA& b, int64_t floor,
                           const std::string& why) { record_differences(a, b, floor, why, state); };
    auto a0 = frame(**comp, 0);
    if (!a0) return a0.error();
    auto b1 = frame(**comp, 1);
    if (!b1) return b1.error();
    auto a0_again = frame(**comp, 0);
    if (!a0_again) return a0_again.error();
    w.case_picture("output.floor0", *a0);
    w.case_picture("output.floor0.after-floor1", *a0_again);
    expect_same(*a0, *a0_again, global ? -1 : 0,
                "floor 0 changed after floor 1 was rendered (state kept between floors)");

    if (!global) {
        // Floor 1 with the plugin on floor 1 only: what floor 0's instance does must not matter.
        SceneLayout alone = layout;
        alone.floor_effects[0].clear();
        auto alone_comp = load_layout(c, s, w, alone, "alone");
        if (!alone_comp) return alone_comp.error();
        if (!*alone_comp) return {};
        auto b1_alone = frame(**alone_comp, 1);
        if (!b1_alone) return b1_alone.error();
        expect_same(*b1, *b1_alone, 1,
                    "floor 1 differs when floor 0 also runs the plugin (state shared between "
                    "floors' instances)");
    }
    {
        auto second = load_layout(c, s, w, layout, "scene");
        if (!second) return second.error();
        if (!*second) return {};
        auto a0_reloaded = frame(**second, 0);
        if (!a0_reloaded) return a0_reloaded.error();
        expect_same(*a0, *a0_reloaded, global ? -1 : 0,
                    "a second load of the same scene gives a different floor 0 (state kept "
                    "between loads)");
    }
    w.add(state.finish());

    // Memory: after a warm-up, many more switches must not grow what the process holds.
    CheckResult memory;
    memory.check = "memory";
    constexpr uint32_t kWarmUp = 10;
    const size_t images_before = (**comp).images_held().size();
    uint64_t resident_warm = 0;
    for (uint32_t i = 0; i < kWarmUp + c.spec.switches; ++i) {
        if (i == kWarmUp) resident_warm = resident_bytes();
        auto stats = (**comp).render(i % 2, c.spec.time);
        if (!stats) return stats.error();
        if (stats->targets_allocated || stats->images_loaded || stats->shaders_compiled ||
            stats->pipelines_created) {
            memory.verdict = Verdict::Fail;
            memory.message =
                fmt::format("switch {} allocated, loaded or compiled during a frame", i);
        }
    }
    const int64_t growth = int64_t(resident_bytes()) - int64_t(resident_warm);
    // Measured growth on lavapipe is 0 KiB over 20 to 200 switches (lighting, bloom); the
    // allowance leaves room for malloc growing an arena by its 128 KiB steps a few times. A
    // leak of one 160x96 rgba16f image per switch (120 KiB) exceeds it within 9 switches.
    constexpr int64_t kAllowance = 1ll << 20;
    if (memory.verdict == Verdict::Pass) {
        if ((**comp).images_held().size() != images_before || growth > kAllowance) {
            memory.verdict = Verdict::Fail;
            memory.message = fmt::format(
                "memory grew by {} KiB over {} floor switches (allowance {} KiB); images held "
                "{} -> {}",
                growth / 1024, c.spec.switches, kAllowance / 1024, images_before,
                (**comp).images_held().size());
        } else {
            memory.message = fmt::format(
                "resident memory changed by {} KiB over {} floor switches (allowance {} KiB); "
                "{} images held before and after",
                growth / 1024, c.spec.switches, kAllowance / 1024, images_before);
        }
    }
    w.add(memory);
    return {};
}

// The effect on floor 1 of 3 must change the composite only where floor 1 has coverage.
Result<void> run_floor_isolation(const CaseContext& c, Session& s, CaseWriter& w) {
    SceneLayout layout = plugin_everywhere(c);
    for (uint32_t f = 0; f < layout.floor_effects.size(); ++f)
        if (f != 1) layout.floor_effects[f].clear();
    auto comp = load_layout(c, s, w, layout, "scene");
    if (!comp) return comp.error();
    if (!*comp) return {};
    const uint32_t top = c.spec.floors - 1;
    auto floor1 = render_floor(**comp, 1, c.spec.time);
    if (!floor1) return floor1.error();
    ACETATE_TRY((**comp).render(top, c.spec.time));
    auto with_effect = (**comp).read_accumulation();
    if (!with_effect) return with_effect.error();
    (**comp).set_effects_enabled(false);
    ACETATE_TRY((**comp).render(top, c.spec.time));
    auto without = (**comp).read_accumulation();
    (**comp).set_effects_enabled(true);
    if (!without) return without.error();

    CheckAccumulator isolation("floor-isolation",
                               "the composite changed only where floor 1 has coverage");
    record_differences(*without, *with_effect, -1,
                       "outside floor 1's coverage the composite changed", isolation,
                       &floor1.value());
    w.case_picture("composite.without-effect", *without);
    w.case_picture("composite.with-effect", *with_effect);
    w.add(isolation.finish());
    return {};
}

// Each parameter at its minimum and at its maximum, on a scene with lights and every mask
// kind the plugin reads, at three times, with the other parameters at their defaults, then all
// at their minimums, then all at their maximums (a parameter may matter only when another
// allows it, like a night level by day): identical outputs throughout mean the parameter is
// not connected to anything (docs/design.md, L-connected).
Result<void> run_disconnected(const CaseContext& c, Session& s, CaseWriter& w) {
    constexpr float kTimes[] = {0.0f, 0.37f, 1.9f};
    enum class Others { Default, Min, Max };
    std::vector<std::string> disconnected;
    for (const ParamInfo& p : c.plugin.params) {
        if (p.min_value == p.max_value) continue;
        bool connected = false;
        for (Others others : {Others::Default, Others::Min, Others::Max}) {
            std::vector<std::string> digests[2];
            for (int end = 0; end < 2; ++end) {
                json params = json::object();
                for (const ParamInfo& q : c.plugin.params)
                    if (others != Others::Default)
                        params[q.name] = others == Others::Min ? q.min_value : q.max_value;
                params[p.name] = end ? p.max_value : p.min_value;
                const std::string name = fmt::format("{}.{}", p.name, end ? "max" : "min");
                auto comp = load_layout(c, s, w, plugin_everywhere(c, params), name);
                if (!comp) return comp.error();
                if (!*comp) return {};
                for (float t : kTimes) {
                    ACETATE_TRY((**comp).render(c.spec.floors - 1, t));
                    auto image = c.plugin.is_global() ? (**comp).read_accumulation()
                                                      : (**comp).read_active_floor();
                    if (!image) return image.error();
                    digests[end].push_back(digest_images({&image.value()}));
                }
            }
            if (digests[0] != digests[1]) {
                connected = true;
                break;
            }
        }
        if (!connected) disconnected.push_back(p.name);
    }
    CheckResult check;
    check.check = "disconnected-parameters";
    if (disconnected.empty()) {
        check.message = fmt::format(
            "each of the {} parameters changed the output between its minimum and maximum",
            c.plugin.params.size());
    } else {
        check.verdict = Verdict::Fail;
        check.violations = disconnected.size();
        check.message = fmt::format(
            "parameter{} {} changed nothing between minimum and maximum ({}x{} scene with 3 "
            "lights{}, times 0, 0.37 and 1.9, the other parameters at default, minimum and "
            "maximum): not connected to the shader?",
            disconnected.size() == 1 ? "" : "s", fmt::join(disconnected, ", "), c.spec.width,
            c.spec.height,
            c.plugin.masks.empty() ? ""
                                   : fmt::format(" and masks {}", fmt::join(c.plugin.masks, ", ")));
    }
    w.add(check);
    return {};
}

// ---- integration ------------------------------------------------------------------------

constexpr double kHalfMax = 65504.0;
// One rgba16f rounding: within one ULP, 2^-10 of the value (Vulkan allows rounding toward zero
// as well as to nearest), or 2^-24 for subnormals (as in tests/composite_accuracy_test.cpp).
constexpr double kHalfRelative = 0x1p-10, kHalfAbsolute = 0x1p-24;

// The plugin with the other integrated plugins on four floors: each floor's output must not
// depend on the other floors' effects, and the composite must be the "over" of the floors as
// each was rendered alone (a reference built on the CPU, compared in the manner of idiff).
Result<void> run_integration(const CaseContext& c, Session& s, CaseWriter& w) {
    const CaseSpec& spec = c.spec;
    SceneLayout layout;
    layout.width = spec.width;
    layout.height = spec.height;
    layout.floor_effects.resize(spec.floors);
    std::vector<bool> expanding(spec.floors, false), under_test_floor(spec.floors, false);
    for (uint32_t f = 0; f < spec.floors; ++f)
        layout.floors.push_back(make_floor_input(spec.pattern, spec.width, spec.height, f,
                                                 spec.floors, spec.seed, c.plugin.masks));
    // The plugin under test on the odd floors, floor companions round-robin on the even ones.
    size_t next_companion = 0;
    std::vector<const CompanionPlugin*> floor_companions;
    for (const CompanionPlugin& other : spec.companions) {
        if (other.scope == "global")
            layout.global_effects.push_back({other.id, json::object(), ""});
        else
            floor_companions.push_back(&other);
    }
    for (uint32_t f = 0; f < spec.floors; ++f) {
        if (!c.plugin.is_global() && f % 2 == 1) {
            layout.floor_effects[f].push_back(under_test(c));
            under_test_floor[f] = true;
            expanding[f] = c.plugin.is_expanding();
        } else if (!floor_companions.empty()) {
            const CompanionPlugin* other =
                floor_companions[next_companion++ % floor_companions.size()];
            layout.floor_effects[f].push_back({other->id, json::object(), ""});
        }
    }
    if (c.plugin.is_global()) layout.global_effects.push_back(under_test(c));
    auto comp = load_layout(c, s, w, layout, "stack");
    if (!comp) return comp.error();
    if (!*comp) return {};
    // Companions' coverage, from their descriptors (already loaded by the scene).
    for (uint32_t f = 0; f < spec.floors; ++f)
        for (const SceneEffect& effect : layout.floor_effects[f]) {
            auto plugin = s.renderer->plugins().load(effect.plugin);
            if (plugin && plugin.value()->descriptor.coverage == ACETATE_COVERAGE_EXPANDING)
                expanding[f] = true;
        }
    // The whole stack once first, so that every floor's instance has run before any floor is
    // captured: state a higher floor leaves behind would show in a lower floor's capture.
    ACETATE_TRY((**comp).render(spec.floors - 1, spec.time));
    std::vector<Capture> captures;
    for (uint32_t f = 0; f < spec.floors; ++f) {
        auto capture = capture_floor(**comp, f, spec.time);
        if (!capture) return capture.error();
        captures.push_back(std::move(capture.value()));
        const ImageRGBA& out = captures.back().output;
        w.case_picture(fmt::format("output.floor{}", f), out);
    }

    // The contract on the plugin's own floors (or the composite it ran on).
    std::vector<FloorImages> checked;
    std::optional<Capture> global;
    if (c.plugin.is_global()) {
        auto capture = capture_global(**comp, spec.floors - 1, spec.time);
        if (!capture) return capture.error();
        global = std::move(capture.value());
        checked.push_back({-1, &global->input, &global->output});
    }
    for (uint32_t f = 0; f < spec.floors; ++f)
        if (under_test_floor[f])
            checked.push_back({int64_t(f), &captures[f].input, &captures[f].output});
    std::map<std::string, std::map<int64_t, ImageRGBA>> heat;
    w.add_all(check_contract(checked, c.plugin.is_expanding(), &heat), heat);

    // Cross-floor: each floor with effects, rendered with no effect on any other floor.
    CheckAccumulator cross("cross-floor",
                           "every floor's output was the same with and without the other "
                           "floors' effects");
    for (uint32_t f = 0; f < spec.floors; ++f) {
        if (layout.floor_effects[f].empty()) continue;
        SceneLayout alone = layout;
        for (uint32_t g = 0; g < spec.floors; ++g)
            if (g != f) alone.floor_effects[g].clear();
        auto alone_comp = load_layout(c, s, w, alone, fmt::format("alone{}", f));
        if (!alone_comp) return alone_comp.error();
        if (!*alone_comp) return {};
        auto output = render_floor(**alone_comp, f, spec.time);
        if (!output) return output.error();
        record_differences(*output, captures[f].output, f,
                           "alone, then with the other floors' effects", cross);
    }
    w.add(cross.finish());

    // Reference: the floors' outputs composited on the CPU in double precision, gated as the
    // host gates them (stencil where the tiles drew, or by alpha after an expanding effect).
    (**comp).set_effects_enabled(true, false);
    ACETATE_TRY((**comp).render(spec.floors - 1, spec.time));
    auto composite = (**comp).read_accumulation();
    (**comp).set_effects_enabled(true, true);
    if (!composite) return composite.error();
    const size_t pixels = size_t(spec.width) * spec.height;
    std::vector<double> exact(pixels * 4, 0.0), peak(pixels * 4, 0.0);
    for (uint32_t f = 0; f < spec.floors; ++f)
        for (size_t i = 0; i < pixels; ++i) {
            const float* in = &captures[f].input.pixels[i * 4];
            const float* out = &captures[f].output.pixels[i * 4];
            const bool drawn = expanding[f]
                                   ? (out[0] != 0 || out[1] != 0 || out[2] != 0 || out[3] != 0)
                                   : in[3] > 0.0f;
            if (!drawn) continue;
            for (int ch = 0; ch < 4; ++ch) {
                double& v = exact[i * 4 + ch];
                v = out[ch] + (1.0 - out[3]) * v;
                peak[i * 4 + ch] = std::max(peak[i * 4 + ch], std::abs(v));
            }
        }
    ImageRGBA reference(spec.width, spec.height);
    for (size_t i = 0; i < exact.size(); ++i)
        reference.pixels[i] = float(std::clamp(exact[i], -kHalfMax, kHalfMax));
    // In the manner of idiff's -fail / -warn / -failpercent 0: each blend rounds once, and
    // "over" only scales earlier errors by (1 - a) <= 1, so a correct composite is within
    // `floors` roundings of the running peak (fail above, at any pixel); warn above half that.
    // Where the exact value exceeds 65504 the target may hold 65504 or infinity.
    CheckResult ref;
    ref.check = "reference";
    uint64_t warn_pixels = 0, fail_pixels = 0;
    double worst_steps = 0;
    int64_t worst_x = 0, worst_y = 0;
    for (uint32_t y = 0; y < spec.height; ++y)
        for (uint32_t x = 0; x < spec.width; ++x) {
            const size_t i = size_t(y) * spec.width + x;
            double pixel_steps = 0;
            for (int ch = 0; ch < 4; ++ch) {
                // Per channel: alpha's tolerance must not grow with an HDR colour's.
                const double rounding = kHalfRelative * peak[i * 4 + ch] + kHalfAbsolute;
                const double e = exact[i * 4 + ch];
                const float g = composite->pixels[i * 4 + ch];
                double steps = 0;
                const bool saturated =
                    std::abs(e) > kHalfMax &&
                    (std::isinf(g) || std::abs(g) >= kHalfMax * (1 - spec.floors * kHalfRelative));
                if (saturated && std::signbit(e) == std::signbit(g))
                    steps = 0;
                else if (std::isfinite(g))
                    steps = std::abs(e - g) / rounding;
                else
                    steps = 1e30;  // NaN, or infinity where the exact value is finite
                pixel_steps = std::max(pixel_steps, steps);
            }
            if (pixel_steps > 0.5 * spec.floors) ++warn_pixels;
            if (pixel_steps > spec.floors) ++fail_pixels;
            if (pixel_steps > worst_steps) {
                worst_steps = pixel_steps;
                worst_x = x;
                worst_y = y;
            }
        }
    const double fail_steps = spec.floors;
    ref.message = fmt::format(
        "composite against the CPU reference: worst {:.3g} roundings at ({}, {}); fail above {} "
        "(one per blend), warn above {}; {} pixels above warn, {} above fail",
        worst_steps, worst_x, worst_y, fail_steps, fail_steps / 2, warn_pixels, fail_pixels);
    if (worst_steps > fail_steps) {
        ref.verdict = Verdict::Fail;
        ref.violations = fail_pixels;
        Violation v;
        v.x = worst_x;
        v.y = worst_y;
        std::memcpy(v.input.data(), reference.at(uint32_t(worst_x), uint32_t(worst_y)), 16);
        std::memcpy(v.output.data(), composite->at(uint32_t(worst_x), uint32_t(worst_y)), 16);
        v.what = "reference then composite";
        ref.examples.push_back(v);
    } else if (worst_steps > fail_steps / 2) {
        ref.verdict = Verdict::Warn;
    }
    w.case_picture("composite", *composite);
    w.case_picture("reference", reference);
    w.add(ref);
    return {};
}

}  // namespace

fs::path case_result_file(const fs::path& case_directory) {
    return case_directory / "result.json";
}

Result<CaseResult> run_case(const CaseContext& c) {
    std::error_code ec;
    fs::create_directories(c.case_directory, ec);
    if (ec)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot create: {}",
                                                     c.case_directory.string(), ec.message()));
    auto session = open_session(c);
    if (!session) return session.error();
    CaseWriter writer(c);
    Result<void> ran;
    switch (c.spec.kind) {
        case CaseKind::Contract:
            ran = run_contract(c, *session, writer);
            break;
        case CaseKind::Determinism:
            ran = run_determinism(c, *session, writer);
            break;
        case CaseKind::StateIsolation:
            ran = run_state_isolation(c, *session, writer);
            break;
        case CaseKind::FloorIsolation:
            ran = run_floor_isolation(c, *session, writer);
            break;
        case CaseKind::Disconnected:
            ran = run_disconnected(c, *session, writer);
            break;
        case CaseKind::Integration:
            ran = run_integration(c, *session, writer);
            break;
    }
    if (!ran) return ran.error();
    // Close Vulkan first: messages at teardown (objects left alive) count too.
    session->renderer.reset();
    session->context.reset();
    return writer.finish();
}

}  // namespace acetate::harness
