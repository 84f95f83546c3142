// Determinism, state isolation (frames, floors and loads in one process) and floor isolation.
#include <fmt/format.h>

#include "case_kinds.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;
using nlohmann::json;

// Two frames of each floor must match bit for bit; the digest lets the parent compare
// processes: two fresh ones, and one that first loaded other scenes and rendered earlier frames
// (determinism/after-history). The outputs are kept as EXR so the parent can show where they
// differ.
Result<void> run_determinism(const CaseContext& c, Session& s, CaseWriter& w) {
    auto history = render_history(c, s, w);
    if (!history) return history.error();
    if (!*history) return {};
    auto comp = load_layout(c, s, w, case_layout(c), "scene");
    if (!comp) return comp.error();
    if (!*comp) return {};
    ACETATE_TRY(render_earlier_frames(**comp, c));
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

namespace {

// Measured on lavapipe: lighting and bloom grow by 0 KiB over 22 loads (strictness 5)
// after the warm-up. A build() leaking 64 KiB per instance (two per load here) exceeds the
// allowance within 16 loads.
constexpr int64_t kLoadAllowance = 2ll << 20;

struct LoadGrowth {
    bool loaded = true;  // false: a load failed (recorded as the case's "load" failure)
    uint32_t loads = 0;
    int64_t growth = 0;  // bytes of resident memory, after the warm-up loads
};

// Loads the scene again and again, rendering every floor of each load once.
Result<LoadGrowth> measure_loads(const CaseContext& c, Session& s, CaseWriter& w,
                                 const SceneLayout& layout) {
    auto scene = write_scene(layout, c.case_directory, "reload");
    if (!scene) return scene.error();
    constexpr uint32_t kWarmUp = 3;
    LoadGrowth out;
    out.loads = 2 + c.spec.switches / 5;  // 22 at the default strictness
    uint64_t resident_warm = 0;
    for (uint32_t i = 0; i < kWarmUp + out.loads; ++i) {
        if (i == kWarmUp) resident_warm = resident_bytes();
        auto comp = load_scene(c, s, w, *scene);
        if (!comp) return comp.error();
        if (!*comp) {
            out.loaded = false;
            return out;
        }
        for (uint32_t f = 0; f < c.spec.floors; ++f) ACETATE_TRY((**comp).render(f, c.spec.time));
    }
    out.growth = int64_t(resident_bytes()) - int64_t(resident_warm);
    return out;
}

}  // namespace

// Floors 0, 1, 0 in one load; each floor alone; a second load; memory over many switches.
Result<void> run_state_isolation(const CaseContext& c, Session& s, CaseWriter& w) {
    const SceneLayout layout = case_layout(c);
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

    // Memory per frame: after a warm-up, many more frames as an interactive host renders them
    // (the time advancing at 60 frames a second, the active floor switching every frame) must
    // not grow what the process holds: resident memory on the host; targets, images,
    // shaders and pipelines on the device.
    CheckResult memory;
    memory.check = "memory";
    constexpr uint32_t kWarmUp = 10;
    const size_t images_before = (**comp).images_held().size();
    uint64_t resident_warm = 0;
    for (uint32_t i = 0; i < kWarmUp + c.spec.switches; ++i) {
        if (i == kWarmUp) resident_warm = resident_bytes();
        auto stats = (**comp).render(i % 2, c.spec.time + double(i) / 60.0);
        if (!stats) return stats.error();
        if (stats->targets_allocated || stats->images_loaded || stats->shaders_compiled ||
            stats->pipelines_created) {
            memory.verdict = Verdict::Fail;
            memory.message = fmt::format("frame {} allocated, loaded or compiled", i);
        }
    }
    const int64_t growth = int64_t(resident_bytes()) - int64_t(resident_warm);
    // Measured growth on lavapipe is 0 KiB over 20 to 200 frames (lighting, bloom); the
    // allowance leaves room for malloc growing an arena by its 128 KiB steps a few times. A
    // leak of one 160x96 rgba16f image per frame (120 KiB) exceeds it within 9 frames.
    constexpr int64_t kAllowance = 1ll << 20;
    if (memory.verdict == Verdict::Pass) {
        if ((**comp).images_held().size() != images_before || growth > kAllowance) {
            memory.verdict = Verdict::Fail;
            memory.message = fmt::format(
                "memory grew by {} KiB over {} frames, each at a later time on the other floor "
                "(allowance {} KiB); images held {} -> {}",
                growth / 1024, c.spec.switches, kAllowance / 1024, images_before,
                (**comp).images_held().size());
        } else {
            memory.message = fmt::format(
                "resident memory changed by {} KiB over {} frames, each at a later time on the "
                "other floor (allowance {} KiB); {} images held before and after",
                growth / 1024, c.spec.switches, kAllowance / 1024, images_before);
        }
    }
    comp->reset();

    // Memory across loads: build() runs once per instance and load, so a leak there shows only
    // when the same scene is loaded again and again in one process.
    if (memory.verdict == Verdict::Pass) {
        auto loads = measure_loads(c, s, w, layout);
        if (!loads) return loads.error();
        if (!loads->loaded) return {};
        if (loads->growth > kLoadAllowance) {
            memory.verdict = Verdict::Fail;
            memory.message = fmt::format(
                "resident memory grew by {} KiB over {} loads of the same scene (allowance {} "
                "KiB): does build() leak?",
                loads->growth / 1024, loads->loads, kLoadAllowance / 1024);
        } else {
            memory.message +=
                fmt::format("; {} KiB over {} loads of the scene (allowance {} KiB)",
                            loads->growth / 1024, loads->loads, kLoadAllowance / 1024);
        }
    }
    w.add(memory);
    return {};
}

// The effect on floor 1 of 3 must change the composite only where floor 1 has coverage.
Result<void> run_floor_isolation(const CaseContext& c, Session& s, CaseWriter& w) {
    SceneLayout layout = case_layout(c);
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

void plan_determinism(const PlanContext& context, Planner& p) {
    // Two fresh processes, and a third that renders other scenes and frames first: all three
    // must give the same bytes. Their poisons differ, so a read of unwritten memory differs.
    const Poison poisons[] = {Poison::Large, Poison::Plain, Poison::NaN};
    for (int run = 1; run <= 3; ++run) {
        CaseSpec s = p.contract(run < 3 ? fmt::format("determinism/run-{}", run)
                                        : std::string("determinism/after-history"),
                                run < 3 ? "the same case in two processes, two frames each"
                                        : "the same case after two other loads and six frames",
                                192, 128, Pattern::Standard, 2);
        s.kind = CaseKind::Determinism;
        s.poison = poisons[run - 1];
        if (run == 3) {
            s.prior_loads = 2;
            s.frames = 6;
        }
        s.seed = case_seed(context.run_seed, "determinism");  // every run: the same inputs
        p.add(s, true);
    }
    // Run 1 again (its poison too), in a process started afresh without the Vulkan validation
    // layer, as users run their hosts: the layer's findings come from the runs above, and a
    // plugin that behaves only while the layer's library is in its process differs here.
    CaseSpec plain = p.contract("determinism/without-layer",
                                "the same case as run-1, in a process without the Vulkan "
                                "validation layer",
                                192, 128, Pattern::Standard, 2);
    plain.kind = CaseKind::Determinism;
    plain.poison = poisons[0];
    plain.validation_layer = false;
    plain.seed = case_seed(context.run_seed, "determinism");
    p.add(plain, true);
}

void plan_state_isolation(const PlanContext& context, Planner& p) {
    CaseSpec state = p.contract("isolation/state",
                                "floors 0, 1, 0; each floor alone; a second load; then many "
                                "switches and loads for memory growth",
                                160, 96, Pattern::Standard, 2);
    state.kind = CaseKind::StateIsolation;
    state.switches = uint32_t(20 * context.strictness);
    p.add(state);
}

void plan_floor_isolation(const PlanContext& context, Planner& p) {
    if (!context.floor_effect()) return;
    CaseSpec floor =
        p.contract("isolation/floors", "the composite with and without the effect on floor 1 of 3",
                   192, 128, Pattern::Standard, 3);
    floor.kind = CaseKind::FloorIsolation;
    p.add(floor);
}

}  // namespace acetate::harness
