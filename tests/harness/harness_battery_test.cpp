// The broken-plugin battery: `acetate-harness validate` on each plugin of
// tests/plugins/harness must flag exactly the rule that plugin breaks (each source's first
// comment names it, and the check that must catch it) and nothing else. The two controls
// (well_behaved, expanding_glow) must pass every check.
//
// Every dimension of the input model (harness/input_model.hpp) and every rule has a plugin
// that only that dimension or rule exposes: its failures must come from the dimension's own
// cases, or from a combined/* point that drew the same value, and from no other case.
//
// Each plugin is validated once, at strictness 1 and only up to ALPHA_TESTED (integration is
// not what these plugins are about), in a private folder with a private registry, and that one
// report is asserted on: the worst verdict of every check over the cases, crashes and
// timeouts, the exit status, the reproduce commands, and the plugin's own evidence (the
// example pixel of a NaN, the alpha step, the parameter named). colour_at_zero also re-runs
// one failing case from its reproduce command.
//
// At strictness 1 a plugin's run takes 8 to 30 s here (2 cores, lavapipe).

#include "harness_battery.hpp"

namespace acetate::battery {
namespace {

// ---- what each plugin must give ----------------------------------------------------------

struct Expectation {
    std::string plugin;             // file stem in ACETATE_HARNESS_PLUGIN_DIR
    std::set<std::string> failing;  // checks whose worst verdict is FAIL
    std::set<std::string> skipped;  // checks whose worst verdict is SKIP, by design
    bool process_failures = false;  // cases are expected to CRASH or TIME OUT (see `extra`)
    void (*extra)(const HarnessRun&) = nullptr;  // the plugin's own evidence
    int timeout = kTimeoutSeconds;               // --timeout
};

void PrintTo(const Expectation& e, std::ostream* os) {
    *os << e.plugin;
}

// colour_at_zero: rgb (0.25, 0, 0) where a = 0. The example says so; and the failing case
// re-run alone by its reproduce command gives the same count, while another seed gives the
// case another seed (contract/standard has transparent pixels whatever its seed).
void colour_at_zero(const HarnessRun& run) {
    bool first = true;
    for (const json* c : run.check_cases.at("premultiplied")) {
        const json* check = HarnessRun::find_check(*c, "premultiplied");
        if (verdict_of((*check)["verdict"]) != Verdict::Fail) continue;
        ASSERT_FALSE((*check)["examples"].empty()) << c->dump(2);
        const json& example = (*check)["examples"][0];
        const std::string what = example["what"].get<std::string>();
        if (first) {
            EXPECT_TRUE(contains(what, "a = 0 ")) << what;
            EXPECT_TRUE(contains(what, "rgb = (0.25, 0, 0)")) << what;
            EXPECT_TRUE(contains((*check)["message"].get<std::string>(), what))
                << (*check)["message"];
            first = false;
        }
        EXPECT_EQ(number(example["output"][0]), 0.25f) << example.dump();
        EXPECT_EQ(number(example["output"][3]), 0.0f) << example.dump();
        EXPECT_EQ(number(example["input"][3]), 0.0f) << example.dump();
    }
    EXPECT_FALSE(first) << "no case failed premultiplied";

    // Reproduce contract/standard exactly as the report says to.
    const std::string id = "contract/standard";
    const json* full = run.find_case(id);
    ASSERT_NE(full, nullptr) << "no case " << id;
    const json* full_check = HarnessRun::find_check(*full, "premultiplied");
    ASSERT_NE(full_check, nullptr);
    ASSERT_EQ(verdict_of((*full_check)["verdict"]), Verdict::Fail) << full->dump(2);
    const std::string reproduce = (*full)["reproduce"].get<std::string>();
    const std::string prefix = "acetate-harness validate ";
    ASSERT_EQ(reproduce.rfind(prefix, 0), 0u) << reproduce;
    // The reproduce line is complete: the run's registry, its time limit, and a report folder
    // of its own beside the full run's (which it must not overwrite).
    const fs::path again_dir = run.report_dir.string() + "-repro";
    for (const std::string& part :
         {"--registry " + run.registry.string(), "--report " + again_dir.string(),
          "--timeout " + std::to_string(kTimeoutSeconds)})
        EXPECT_NE(reproduce.find(part), std::string::npos) << part << " in " << reproduce;
    const std::string command =
        "cd " + shell_quote(run.dir.string()) + " && " + test::harness_environment() + " " +
        shell_quote(ACETATE_HARNESS_PATH) + " validate " + reproduce.substr(prefix.size()) +
        " --no-signoffs --jobs 2 --stage alpha-tested";
    const test::CommandResult again = test::run_command(command, run.dir);
    EXPECT_EQ(again.code, 1) << again.describe();
    const json report = read_report(again_dir);
    ASSERT_EQ(report["cases"].size(), 1u) << again.describe();
    const json& one = report["cases"][0];
    EXPECT_EQ(one["id"], id);
    EXPECT_EQ(one["seed"], (*full)["seed"]);
    EXPECT_EQ(one["verdict"], "FAIL");
    const json* check = HarnessRun::find_check(one, "premultiplied");
    ASSERT_NE(check, nullptr) << one.dump(2);
    EXPECT_EQ((*check)["verdict"], "FAIL");
    EXPECT_EQ((*check)["violations"], (*full_check)["violations"]);
    EXPECT_EQ((*check)["examples"], (*full_check)["examples"]);
    ASSERT_EQ(report["stages"].size(), 1u);
    EXPECT_EQ(report["stages"][0]["recorded"], false);

    // Another run seed: another case seed (and so other inputs).
    const fs::path other_dir = run.dir / "other-seed";
    const test::CommandResult other =
        validate(run.dir, run.plugin, other_dir, "--seed 2 --case " + id);
    EXPECT_EQ(other.code, 1) << other.describe();
    const json other_report = read_report(other_dir);
    ASSERT_EQ(other_report["cases"].size(), 1u) << other.describe();
    EXPECT_EQ(other_report["cases"][0]["id"], id);
    EXPECT_NE(other_report["cases"][0]["seed"], (*full)["seed"]);
    EXPECT_TRUE(contains(other_report["cases"][0]["reproduce"].get<std::string>(), "--seed 2"));
}

// alpha_half_step: every example's alpha went up by exactly one half-float step.
void alpha_half_step(const HarnessRun& run) {
    size_t examples = 0;
    for (const json* c : run.check_cases.at("coverage")) {
        const json* check = HarnessRun::find_check(*c, "coverage");
        for (const json& example : (*check)["examples"]) {
            const float in = number(example["input"][3]), out = number(example["output"][3]);
            EXPECT_GT(in, 0.0f) << example.dump();
            EXPECT_LT(in, 1.0f) << example.dump();
            Imath::half next(in);
            ASSERT_EQ(float(next), in) << "input alpha is not a half: " << example.dump();
            next.setBits(next.bits() + 1);
            EXPECT_EQ(out, float(next)) << example.dump();
            ++examples;
        }
    }
    EXPECT_GT(examples, 0u);
}

// nan_pixel: the only non-finite value is the red channel at the canvas centre.
void nan_pixel(const HarnessRun& run) {
    size_t failing = 0;
    for (const json* c : run.check_cases.at("finite")) {
        const json* check = HarnessRun::find_check(*c, "finite");
        if (verdict_of((*check)["verdict"]) != Verdict::Fail) continue;
        ++failing;
        const json spec = run.case_spec((*c)["id"].get<std::string>());
        const int64_t cx = spec.value("width", 0) / 2, cy = spec.value("height", 0) / 2;
        // One NaN per floor at most, and the composite of the floors shows it once more.
        const int64_t floors = spec.value("floors", 1);
        EXPECT_LE((*check)["violations"].get<int64_t>(), floors + 1) << check->dump(2);
        ASSERT_FALSE((*check)["examples"].empty());
        for (const json& example : (*check)["examples"]) {
            EXPECT_GE(example["floor"].get<int64_t>(), -1) << example.dump();
            EXPECT_LT(example["floor"].get<int64_t>(), floors) << example.dump();
            EXPECT_EQ(example["x"], cx) << (*c)["id"] << ": " << example.dump();
            EXPECT_EQ(example["y"], cy) << (*c)["id"] << ": " << example.dump();
            EXPECT_TRUE(std::isnan(number(example["output"][0]))) << example.dump();
            EXPECT_TRUE(contains(example["what"].get<std::string>(), "NaN")) << example.dump();
        }
    }
    EXPECT_GT(failing, 0u);
    // An opaque floor covers the centre: that case must catch it.
    const json* opaque = run.find_case("inputs/opaque");
    ASSERT_NE(opaque, nullptr);
    const json* check = HarnessRun::find_check(*opaque, "finite");
    ASSERT_NE(check, nullptr);
    EXPECT_EQ((*check)["verdict"], "FAIL") << opaque->dump(2);
}

// nondeterministic: the second process differs from the first; state isolation is not judged.
void nondeterministic(const HarnessRun& run) {
    const json* run2 = run.find_case("determinism/run-2");
    ASSERT_NE(run2, nullptr);
    const json* check = HarnessRun::find_check(*run2, "determinism");
    ASSERT_NE(check, nullptr);
    EXPECT_EQ((*check)["verdict"], "FAIL");
    EXPECT_TRUE(contains((*check)["message"].get<std::string>(),
                         "rendered the same case differently from a fresh process"))
        << (*check)["message"];
    const json* run1 = run.find_case("determinism/run-1");
    ASSERT_NE(run1, nullptr);
    EXPECT_NE((*run1)["output_digest"], (*run2)["output_digest"]);
    const json* state = run.find_case("isolation/state");
    ASSERT_NE(state, nullptr);
    const json* isolation = HarnessRun::find_check(*state, "state-isolation");
    ASSERT_NE(isolation, nullptr);
    EXPECT_EQ((*isolation)["verdict"], "SKIP");
    const std::string message = (*isolation)["message"].get<std::string>();
    EXPECT_TRUE(contains(message, "not judged")) << message;
    EXPECT_TRUE(contains(message, "not deterministic")) << message;
    EXPECT_EQ((*isolation)["violations"], 0);
    EXPECT_TRUE((*isolation)["examples"].empty());
}

// crash_second_floor: every case that builds the plugin for floor 1 kills the child with
// SIGSEGV: two or more floors with the plugin on every floor or on floor 1, or earlier loads
// (render_history's first scene has one floor more than the case, the plugin on each). Every
// other case passes, floors/top-of-five (the plugin on floor 4 only) among them.
void crash_second_floor(const HarnessRun& run) {
    size_t crashed = 0, single = 0;
    for (const json& c : run.report["cases"]) {
        const std::string id = c["id"].get<std::string>();
        const json spec = run.case_spec(id);
        const uint32_t floors = spec.value("floors", 0u);
        const int plugin_floor = spec.value("plugin_floor", -1);
        ASSERT_GT(floors, 0u) << id;
        if ((floors >= 2 && (plugin_floor < 0 || plugin_floor == 1)) ||
            spec.value("prior_loads", 0u) > 0) {
            EXPECT_EQ(c["verdict"], "CRASH") << id << ": " << c.dump(2);
            EXPECT_TRUE(contains(c["message"].get<std::string>(), "SIGSEGV"))
                << id << ": " << c["message"];
            ++crashed;
        } else {
            // A reference case only renders: the battery has no blessed references.
            EXPECT_EQ(c["verdict"], spec["kind"] == "golden" ? "SKIP" : "PASS")
                << id << ": " << c.dump(2);
            ++single;
        }
    }
    EXPECT_GT(crashed, 0u);
    EXPECT_GT(single, 0u);
    const json* standard = run.find_case("contract/standard");
    ASSERT_NE(standard, nullptr);
    EXPECT_EQ((*standard)["verdict"], "PASS");
    const json* top = run.find_case("floors/top-of-five");
    ASSERT_NE(top, nullptr);
    EXPECT_EQ((*top)["verdict"], "PASS");
    EXPECT_TRUE(contains(run.process.out, "CRASH")) << run.describe();
}

// hangs_at_max: the cases that set iterations to its maximum (8), alone or as a point of a
// sweep, are killed at the time limit, twice; the others pass.
void hangs_at_max(const HarnessRun& run) {
    size_t timed_out = 0;
    for (const json& c : run.report["cases"]) {
        const std::string id = c["id"].get<std::string>();
        const json spec = run.case_spec(id);
        // params/disconnected sets each parameter to its maximum in turn; a sweep ends at it.
        auto sets_max = [](const json& params) {
            return params.is_object() && params.contains("iterations") &&
                   params["iterations"].get<double>() >= 8.0;
        };
        bool at_max = id == "params/disconnected" || sets_max(spec.value("params", json()));
        for (const json& point : spec.value("sweep", json::array())) at_max |= sets_max(point);
        if (at_max) {
            EXPECT_EQ(c["verdict"], "TIMEOUT") << id << ": " << c.dump(2);
            // It computes (an endless loop in its shader), so the CPU-time limit kills it; and
            // it hangs again when run once more, so the TIMEOUT counts.
            const std::string message = c["message"].get<std::string>();
            EXPECT_TRUE(contains(message, "no result after " + std::to_string(kHangTimeoutSeconds) +
                                              " s of CPU time"))
                << message;
            EXPECT_TRUE(contains(message, "the same when run once more in a fresh process"))
                << message;
            EXPECT_GE(c["seconds"].get<double>(), kHangTimeoutSeconds - 0.5) << id;
            ++timed_out;
        } else {
            // A reference case only renders: the battery has no blessed references.
            EXPECT_EQ(c["verdict"], spec["kind"] == "golden" ? "SKIP" : "PASS")
                << id << ": " << c.dump(2);
        }
    }
    const json* max = run.find_case("params/max");
    ASSERT_NE(max, nullptr);
    EXPECT_EQ((*max)["verdict"], "TIMEOUT");
    EXPECT_GE(timed_out, 1u);
}

// floor_state_leak: the stamps floor 1 left in `trail` while determinism/after-history rendered
// its earlier frames brighten floor 0 there, so that process differs from a fresh one. Two
// fresh processes agree (whatever their poisons: the stamp is an exact colour), so it is state
// carried between renders, not a read of unwritten memory. isolation/state fails too, and is
// judged: only a difference between fresh processes makes state isolation SKIP.
void floor_state_leak(const HarnessRun& run) {
    for (const char* id : {"determinism/run-1", "determinism/run-2"}) {
        const json* c = run.find_case(id);
        ASSERT_NE(c, nullptr) << id;
        EXPECT_EQ((*c)["verdict"], "PASS") << c->dump(2);
    }
    const json* history = run.find_case("determinism/after-history");
    ASSERT_NE(history, nullptr);
    const json* check = HarnessRun::find_check(*history, "determinism");
    ASSERT_NE(check, nullptr);
    EXPECT_EQ((*check)["verdict"], "FAIL");
    EXPECT_TRUE(
        contains((*check)["message"].get<std::string>(), "rendered other scenes and frames"))
        << (*check)["message"];
    const json* state = run.find_case("isolation/state");
    ASSERT_NE(state, nullptr);
    const json* isolation = HarnessRun::find_check(*state, "state-isolation");
    ASSERT_NE(isolation, nullptr);
    EXPECT_EQ((*isolation)["verdict"], "FAIL");
    EXPECT_TRUE(contains((*isolation)["message"].get<std::string>(), "floor 0 changed"))
        << (*isolation)["message"];
}

// disconnected_param: `radius` is named, `strength` (connected) is not.
void disconnected_param(const HarnessRun& run) {
    const json* c = run.find_case("params/disconnected");
    ASSERT_NE(c, nullptr);
    const json* check = HarnessRun::find_check(*c, "disconnected-parameters");
    ASSERT_NE(check, nullptr);
    const std::string message = (*check)["message"].get<std::string>();
    EXPECT_EQ((*check)["verdict"], "FAIL");
    EXPECT_TRUE(contains(message, "radius")) << message;
    EXPECT_FALSE(contains(message, "strength")) << message;
    EXPECT_EQ((*check)["violations"], 1);
}

// periodic_azimuth (a control): its ends agree, so it is connected only through the interior
// values, and the check says so instead of failing it.
void periodic_azimuth(const HarnessRun& run) {
    const json* c = run.find_case("params/disconnected");
    ASSERT_NE(c, nullptr);
    const json* check = HarnessRun::find_check(*c, "disconnected-parameters");
    ASSERT_NE(check, nullptr);
    const std::string message = (*check)["message"].get<std::string>();
    EXPECT_EQ((*check)["verdict"], "PASS") << message;
    EXPECT_TRUE(contains(message, "azimuth only between interior values")) << message;
}

// watched_only: its NaN shows in the everyday case, so the switch was gone from what it saw.
void watched_only(const HarnessRun& run) {
    const json* c = run.find_case("contract/standard");
    ASSERT_NE(c, nullptr);
    const json* check = HarnessRun::find_check(*c, "finite");
    ASSERT_NE(check, nullptr);
    EXPECT_EQ((*check)["verdict"], "FAIL") << check->dump(2);
    const json* validation = HarnessRun::find_check(*c, "vulkan-validation");
    ASSERT_NE(validation, nullptr);
    EXPECT_EQ((*validation)["verdict"], "PASS")
        << "the layer was still on: " << validation->dump(2);
}

// layer_aware: only the process without the validation layer renders differently, and the
// comparison with run-1 says so; a second process with the layer agrees.
void layer_aware(const HarnessRun& run) {
    const json* without = run.find_case("determinism/without-layer");
    ASSERT_NE(without, nullptr);
    const json* check = HarnessRun::find_check(*without, "determinism");
    ASSERT_NE(check, nullptr);
    EXPECT_EQ((*check)["verdict"], "FAIL") << check->dump(2);
    EXPECT_TRUE(contains((*check)["message"].get<std::string>(), "without the Vulkan validation"))
        << (*check)["message"];
    EXPECT_EQ(HarnessRun::find_check(*without, "vulkan-validation"), nullptr)
        << "the case ran without the layer, so the layer judged nothing there";
    const json* run2 = run.find_case("determinism/run-2");
    ASSERT_NE(run2, nullptr);
    EXPECT_EQ((*HarnessRun::find_check(*run2, "determinism"))["verdict"], "PASS");
}

// undeclared_expansion: alpha grew although the plugin declares coverage-preserving.
void undeclared_expansion(const HarnessRun& run) {
    size_t examples = 0;
    for (const json* c : run.check_cases.at("coverage")) {
        const json* check = HarnessRun::find_check(*c, "coverage");
        for (const json& example : (*check)["examples"]) {
            EXPECT_GT(number(example["output"][3]), number(example["input"][3])) << example.dump();
            EXPECT_TRUE(contains(example["what"].get<std::string>(), "coverage-preserving"))
                << example.dump();
            ++examples;
        }
    }
    EXPECT_GT(examples, 0u);
}

const std::vector<Expectation> kPlugins = {
    {"well_behaved", {}, {}},
    // In inputs/subnormal its neighbours' average of alpha 2^-24 (times strength) rounds to 0
    // in the RGBA16F target while their colour, 1000 times larger, does not: `premultiplied`
    // scales its tolerance by the input's colour-to-alpha ratio so that this passes.
    {"expanding_glow", {}, {}},
    // Its red at alpha 0 is in the whole render's range where a pixel at scale 1/2, whose
    // averaged alpha is above 0, has the input's colour: camera-scale fails there too.
    {"colour_at_zero", {"premultiplied", "camera-scale"}, {}, false, colour_at_zero},
    {"alpha_half_step", {"coverage"}, {}, false, alpha_half_step},
    {"nan_pixel", {"finite"}, {}, false, nan_pixel},
    // State isolation is not judged for a plugin that is not deterministic (validate.cpp).
    // Its loads differ, so the relations, which compare loads, are not judged either.
    {"nondeterministic",
     {"determinism"},
     {"state-isolation", "canvas-size", "format-agreement", "camera-region", "camera-scale"},
     false,
     nondeterministic},
    {"crash_second_floor", {}, {}, true, crash_second_floor},
    {"hangs_at_max", {}, {}, true, hangs_at_max, kHangTimeoutSeconds},
    // determinism/after-history renders floor 1 before floor 0 in its earlier frames, so the
    // leak shows there too; a difference after history only is not nondeterminism, so state
    // isolation is still judged.
    {"floor_state_leak", {"determinism", "state-isolation"}, {}, false, floor_state_leak},
    {"disconnected_param", {"disconnected-parameters"}, {}, false, disconnected_param},
    // Correct only with the harness's switch in its environment, which the case's child takes
    // out once the validation layer is on: caught where a user would see it.
    {"watched_only", {"finite"}, {}, false, watched_only},
    // Correct only while the layer's library is in its process: caught where the case's
    // process never loaded it.
    {"layer_aware", {"determinism"}, {}, false, layer_aware},
    // A control for the check above: a periodic parameter (equal ends) is connected.
    {"periodic_azimuth", {}, {}, false, periodic_azimuth},
    {"undeclared_expansion", {"coverage"}, {}, false, undeclared_expansion},
    // One plugin per dimension of the input model, each caught in that dimension's cases only.
    // A lens centred on the canvas: a floor effect measuring in fractions of the canvas, which
    // rule 8 forbids too (canvas-size); the NaN is its input-model evidence.
    // Its centre is the output's, so at scale 1/2 the lens moves (camera-scale).
    {"odd_width_even_height",
     {"finite", "canvas-size", "camera-scale"},
     {},
     false,
     odd_width_even_height},
    {"high_floor_index", {"finite"}, {}, false, high_floor_index},
    {"no_lights", {"finite"}, {}, false, no_lights},
    {"many_lights", {"load"}, {}, false, many_lights},
    // A flare across the canvas's centre, in canvas coordinates: canvas-size fails too, and so
    // do camera-region and camera-scale (through a camera, acetate_canvas is the output's size).
    {"off_canvas_light",
     {"finite", "canvas-size", "camera-region", "camera-scale"},
     {},
     false,
     off_canvas_light},
    {"tiny_radius", {"finite"}, {}, false, tiny_radius},
    {"huge_radius", {"finite"}, {}, false, huge_radius},
    {"full_mask", {"finite"}, {}, false, full_mask},
    {"absent_mask", {"finite"}, {}, false, absent_mask},
    {"param_interior", {"finite"}, {}, false, param_interior},
    {"negative_time", {"finite"}, {}, false, negative_time},
    {"large_time", {"finite"}, {}, false, large_time},
    {"frame_count", {"finite"}, {}, false, frame_count},
    // The loads dimension, seen by both cases that load other canvases first: finite in
    // loads/after-others, determinism in determinism/after-history (a NaN there is the same NaN
    // in both of its frames, so only the comparison with a fresh process shows it).
    {"other_canvas_load", {"finite", "determinism"}, {}, false, other_canvas_load},
    {"subnormal_alpha", {"finite"}, {}, false, subnormal_alpha},
    // One plugin per edge of the scene format the input model tries (harness/input_fields.cpp).
    {"light_on_floor", {"finite"}, {}, false, light_on_floor},
    {"sun_overhead", {"finite"}, {}, false, sun_overhead},
    {"dark_light", {"finite"}, {}, false, dark_light},
    {"mask_over_one", {"finite"}, {}, false, mask_over_one},
    {"ascii_floor_names", {"non-negative"}, {}, false, ascii_floor_names},
    {"empty_floor_bounds", {}, {}, true, empty_floor_bounds},
    // A control: relies on the host keeping acetate_time_fraction below 1.
    {"fraction_below_one", {}, {}, false, fraction_below_one},
    // One plugin per context and relation (docs/harness.md, "Contexts and relations").
    {"clears_outside_coverage", {"coverage"}, {}, false, clears_outside_coverage},
    // Fractions of acetate_canvas: through a camera that is the output's size, so the falloff
    // moves with the view too (camera-region).
    {"canvas_fraction_falloff",
     {"canvas-size", "camera-region"},
     {},
     false,
     canvas_fraction_falloff},
    {"half_float_positions", {"format-agreement"}, {}, false, half_float_positions},
    // Its pool, placed by render pixels, lands elsewhere at scale 1/2 too (camera-scale).
    {"camera_blind", {"camera-region", "camera-scale"}, {}, false, camera_blind},
    {"scale_blind", {"camera-scale"}, {}, false, scale_blind},
    // Its control: the same darkening with the offsets scaled, and the same tolerance.
    {"scale_aware", {}, {}},
    // One plugin per rule the harness gained.
    {"negative_colour", {"non-negative"}, {}, false, negative_colour},
    {"build_leak", {"memory"}, {}, false, build_leak},
    // Caught through the poison, whose kind (NaN or finite) decides the check; run-1 and run-2
    // have different poisons, so determinism fails too. State isolation renders in one process,
    // with one poison, and passes.
    // The poison it leaves is in the whole render's range at scale 1/2 too (camera-scale).
    {"result_partly_unwritten",
     {"finite", "coverage", "determinism", "camera-scale"},
     {},
     false,
     result_partly_unwritten},
    {"hidden_nan", {"undefined-results"}, {}, false, undefined_everywhere},
    {"inverted_smoothstep", {"undefined-results"}, {}, false, undefined_everywhere},
    {"undefined_at_max", {"undefined-results"}, {}, false, undefined_away_from_defaults},
    // Its neighbour is one texel away, two scene pixels at scale 1/2: a length in texels too.
    {"unclamped_fetch", {"undefined-results", "camera-scale"}, {}, false, undefined_everywhere},
    // ABI 1.1: a declared reach is checked against the same floor shaded over the whole canvas.
    {"declared_reach", {}, {}, false, reach_checked},
    {"short_reach", {"reach"}, {}, false, reach_cut_off},
};

class HarnessBattery : public ::testing::TestWithParam<Expectation> {};

TEST_P(HarnessBattery, FlagsExactlyTheBrokenRule) {
    const Expectation& expect = GetParam();
    HarnessRun run;
    run.dir = test::scratch_dir();
    run.report_dir = run.dir / "report";
    run.registry = run.dir / "registry.json";
    run.plugin = fs::path(ACETATE_HARNESS_PLUGIN_DIR) / (expect.plugin + ".so");
    ASSERT_TRUE(fs::is_regular_file(run.plugin)) << run.plugin;
    run.process = validate(run.dir, run.plugin, run.report_dir, "", expect.timeout);
    SCOPED_TRACE(run.describe());
    ASSERT_TRUE(run.process.code == 0 || run.process.code == 1) << run.describe();

    // Both reports, and a report that is about this plugin.
    ASSERT_TRUE(fs::is_regular_file(run.report_dir / "report.json"));
    EXPECT_TRUE(fs::is_regular_file(run.report_dir / "index.html"));
    EXPECT_TRUE(contains(run.process.out, "report: " + (run.report_dir / "index.html").string()));
    run.report = read_report(run.report_dir);
    ASSERT_TRUE(run.report.contains("cases")) << run.report.dump(2);
    EXPECT_EQ(run.report["error"], "");
    EXPECT_EQ(run.report["id"], "test.harness." + expect.plugin);
    EXPECT_EQ(run.report["strictness"], 1);
    EXPECT_EQ(run.report["seed"], 1);
    ASSERT_FALSE(run.report["cases"].empty());

    // Every check a case reports is registered (harness/checks.hpp), so the waivers and the
    // documents know it.
    for (const json& c : run.report["cases"])
        for (const json& check : c["checks"])
            EXPECT_NE(harness::find_registered_check(check["check"].get<std::string>()), nullptr)
                << "unregistered check " << check["check"] << " in " << c["id"];

    // Each check's worst verdict over the cases; the cases' own verdicts.
    bool anything_failed = false;
    std::vector<std::string> process_failures;
    for (const json& c : run.report["cases"]) {
        const std::string id = c["id"].get<std::string>();
        const Verdict case_verdict = verdict_of(c["verdict"]);
        Verdict worst_check = Verdict::Pass;
        for (const json& check : c["checks"]) {
            const std::string name = check["check"].get<std::string>();
            const Verdict v = verdict_of(check["verdict"]);
            auto [it, fresh] = run.worst.try_emplace(name, v);
            if (!fresh) it->second = std::max(it->second, v);
            run.check_cases[name].push_back(&c);
            worst_check = std::max(worst_check, v);
            if (harness::is_failing(v)) anything_failed = true;
        }
        if (case_verdict == Verdict::Crash || case_verdict == Verdict::Timeout) {
            process_failures.push_back(id + " " + c["verdict"].get<std::string>());
            anything_failed = true;
        } else {
            EXPECT_EQ(case_verdict, worst_check)
                << id << ": a case's verdict is the worst of its checks";
        }
        if (harness::is_failing(case_verdict)) {
            anything_failed = true;
            // Every failure says how to run it again, alone and with its seed.
            const std::string reproduce = c["reproduce"].get<std::string>();
            EXPECT_TRUE(contains(reproduce, "--seed 1")) << id << ": " << reproduce;
            EXPECT_TRUE(contains(reproduce, "--case " + id)) << id << ": " << reproduce;
            EXPECT_TRUE(contains(reproduce, run.plugin.string())) << id << ": " << reproduce;
            EXPECT_TRUE(contains(reproduce, "--strictness 1")) << id << ": " << reproduce;
        }
    }

    // Exactly the expected failures: each listed check FAILs, each listed skip SKIPs, every
    // other check passes. `golden` SKIPs for every plugin here: the battery's plugins have no
    // blessed references, so their reference cases only render (harness_golden_test.cpp
    // judges colour against references).
    for (const auto& [check, verdict] : run.worst) {
        const Verdict want = expect.failing.count(check)                        ? Verdict::Fail
                             : expect.skipped.count(check) || check == "golden" ? Verdict::Skip
                                                                                : Verdict::Pass;
        EXPECT_EQ(harness::to_string(verdict), std::string(harness::to_string(want)))
            << "check " << check;
    }
    for (const std::string& check : expect.failing)
        EXPECT_TRUE(run.worst.count(check)) << "check " << check << " never ran";
    for (const std::string& check : expect.skipped)
        EXPECT_TRUE(run.worst.count(check)) << "check " << check << " never ran";

    // No check may be missing: the contract and validation checks always run; without a
    // crash or a hang, every kind of case reported its checks.
    std::vector<std::string> required = {"premultiplied", "coverage",     "alpha-leak",
                                         "finite",        "non-negative", "vulkan-validation"};
    if (!expect.process_failures) {
        for (const char* check :
             {"determinism", "state-isolation", "memory", "floor-isolation", "undefined-results"})
            required.push_back(check);
        if (run.find_case("params/disconnected")) required.push_back("disconnected-parameters");
    }
    for (const std::string& check : required)
        EXPECT_TRUE(run.worst.count(check)) << "check " << check << " is missing";

    if (expect.process_failures)
        EXPECT_FALSE(process_failures.empty()) << "no case crashed or timed out";
    else
        EXPECT_TRUE(process_failures.empty()) << ::testing::PrintToString(process_failures);

    // The exit status is 0 exactly when nothing failed.
    const bool should_fail = !expect.failing.empty() || expect.process_failures;
    EXPECT_EQ(anything_failed, should_fail);
    EXPECT_EQ(run.process.code, anything_failed ? 1 : 0);
    EXPECT_TRUE(contains(run.process.out, anything_failed ? "FAILED" : "all checks passed"));

    // Only the alpha stage ran; nothing was reviewed, so nothing was recorded.
    ASSERT_EQ(run.report["stages"].size(), 1u) << run.report["stages"].dump(2);
    EXPECT_EQ(run.report["stages"][0]["stage"], "ALPHA_TESTED");
    EXPECT_EQ(run.report["stages"][0]["passed"], !anything_failed);
    EXPECT_EQ(run.report["stages"][0]["recorded"], false);
    EXPECT_EQ(run.report["stage_after"], "UNVALIDATED");
    auto registry = Registry::load(run.registry);
    ASSERT_TRUE(registry) << registry.error().message;
    EXPECT_TRUE(registry->entries().empty());

    if (expect.extra) expect.extra(run);
}

INSTANTIATE_TEST_SUITE_P(Plugins, HarnessBattery, ::testing::ValuesIn(kPlugins),
                         [](const ::testing::TestParamInfo<Expectation>& info) {
                             return info.param.plugin;
                         });

}  // namespace
}  // namespace acetate::battery
