// The evidence of the battery's input-model plugins: every dimension of the input model
// (harness/input_model.hpp) has a plugin that only that dimension exposes, and its failures must
// come from the dimension's own cases, or from a combined/* point that drew the same value, and
// from no other case. harness_battery_test.cpp runs them.

#include "harness_battery.hpp"

namespace acetate::battery {
namespace {

// Whether a case's inputs (the report's `inputs` table, and its case.json) hold the value of
// the dimension a plugin breaks on.
using Exposes = bool (*)(const json& inputs, const json& spec);

// `check` FAILs in each of `own`, the dimension's own cases, and elsewhere only in combined/*
// points; every case it fails in (own or combined) exposes the dimension. Each own case's
// message contains `message_part`.
void fails_only_where(const HarnessRun& run, const std::string& check,
                      const std::set<std::string>& own, Exposes exposes,
                      const std::string& message_part = "") {
    for (const std::string& id : own) {
        const json* c = run.find_case(id);
        ASSERT_NE(c, nullptr) << "no case " << id;
        const json* k = HarnessRun::find_check(*c, check);
        ASSERT_NE(k, nullptr) << id << " has no check " << check << ": " << c->dump(2);
        EXPECT_EQ((*k)["verdict"], "FAIL") << c->dump(2);
        const std::string message = (*k)["message"].get<std::string>();
        EXPECT_TRUE(contains(message, message_part)) << id << ": " << message;
    }
    for (const json& c : run.report["cases"]) {
        const json* k = HarnessRun::find_check(c, check);
        if (!k || (*k)["verdict"] != "FAIL") continue;
        const std::string id = c["id"].get<std::string>();
        EXPECT_TRUE(own.count(id) || id.rfind("combined/", 0) == 0)
            << id << " fails " << check
            << ", which only the dimension's own cases may: " << (*k)["message"];
        EXPECT_TRUE(exposes(c["inputs"], run.case_spec(id)))
            << id << " fails " << check << " without the dimension's value: " << c["inputs"].dump();
    }
}

bool input_is(const json& inputs, const char* dimension, const char* value) {
    return inputs.value(dimension, "") == value;
}

}  // namespace

// odd_width_even_height: the NaN is the pixel at the centre of 37x24, (18, 12), on the floor and
// in the composite.
void odd_width_even_height(const HarnessRun& run) {
    fails_only_where(
        run, "finite", {"sizes/odd-even"},
        [](const json& in, const json&) {
            return contains(in.value("canvas", ""), "(odd x even)");
        },
        "2 pixels fail; first at (18, 12) on floor 0: non-finite value (NaN");
}

// high_floor_index: NaN on floors 3 and up only, and in the composite over them.
void high_floor_index(const HarnessRun& run) {
    fails_only_where(run, "finite", {"floors/top-of-five", "floors/eight"},
                     [](const json&, const json& spec) {
                         const int on = spec.value("plugin_floor", -1);
                         return spec.value("floors", 0) >= 4 && (on < 0 || on >= 3);
                     });
    for (const json* c : run.check_cases.at("finite")) {
        const json* check = HarnessRun::find_check(*c, "finite");
        for (const json& example : (*check)["examples"]) {
            const int64_t floor = example["floor"].get<int64_t>();
            EXPECT_TRUE(floor == -1 || floor >= 3) << (*c)["id"] << ": " << example.dump();
        }
    }
}

void no_lights(const HarnessRun& run) {
    fails_only_where(run, "finite", {"lights/none"},
                     [](const json& in, const json&) { return input_is(in, "lights", "none"); });
}

// many_lights: build() throws for the 65th light; the host's line names std::array's bound.
void many_lights(const HarnessRun& run) {
    fails_only_where(
        run, "load", {"lights/many"},
        [](const json& in, const json&) { return input_is(in, "lights", "many"); },
        "build failed with status 5: array::at: __n (which is 64) >= _Nm (which is 64)");
}

void off_canvas_light(const HarnessRun& run) {
    fails_only_where(run, "finite", {"lights/off-canvas"}, [](const json& in, const json&) {
        return input_is(in, "lights", "off-canvas");
    });
}

void tiny_radius(const HarnessRun& run) {
    fails_only_where(run, "finite", {"lights/tiny-radius"}, [](const json& in, const json&) {
        return input_is(in, "lights", "tiny-radius");
    });
}

void huge_radius(const HarnessRun& run) {
    fails_only_where(run, "finite", {"lights/huge-radius"}, [](const json& in, const json&) {
        return input_is(in, "lights", "huge-radius");
    });
}

void full_mask(const HarnessRun& run) {
    fails_only_where(run, "finite", {"masks/full", "masks/above-one"},
                     [](const json& in, const json&) {
                         return input_is(in, "masks", "full") ||
                                input_is(in, "masks", "above-one") || input_is(in, "masks", "thin");
                     });
}

void absent_mask(const HarnessRun& run) {
    fails_only_where(run, "finite", {"masks/absent"},
                     [](const json& in, const json&) { return input_is(in, "masks", "absent"); });
}

// param_interior: the sweep stops at its first failing value, 1/3, and says so.
void param_interior(const HarnessRun& run) {
    fails_only_where(
        run, "finite", {"params/sweep-blend"},
        [](const json&, const json& spec) {
            auto inside = [](const json& params) {
                const double v = params.value("blend", 0.0);
                return v > 0.25 && v < 0.75;
            };
            bool any = inside(spec.value("params", json::object()));
            for (const json& point : spec.value("sweep", json::array())) any |= inside(point);
            return any;
        },
        "at {\"blend\":0.3333");
}

void negative_time(const HarnessRun& run) {
    fails_only_where(run, "finite", {"time/negative"},
                     [](const json&, const json& spec) { return spec.value("time", 0.0) < 0.0; });
}

// large_time: exp(t / 1000) overflows single precision past t = 88.72e3 s.
void large_time(const HarnessRun& run) {
    fails_only_where(run, "finite", {"time/large"}, [](const json&, const json& spec) {
        return spec.value("time", 0.0) > 88.72e3;
    });
}

// frame_count: NaN from the 9th frame of a load on; no other case renders that many times.
void frame_count(const HarnessRun& run) {
    fails_only_where(run, "finite", {"frames/many"},
                     [](const json&, const json& spec) { return spec.value("frames", 1) > 8; });
}

// other_canvas_load: both cases that load other canvases first, each through its own check.
void other_canvas_load(const HarnessRun& run) {
    const Exposes earlier_loads = [](const json&, const json& spec) {
        return spec.value("prior_loads", 0) > 0;
    };
    fails_only_where(run, "finite", {"loads/after-others"}, earlier_loads);
    fails_only_where(run, "determinism", {"determinism/after-history"}, earlier_loads,
                     "rendered other scenes and frames first");
}

// subnormal_alpha: NaN where alpha is 2^-24.
void subnormal_alpha(const HarnessRun& run) {
    fails_only_where(
        run, "finite", {"inputs/subnormal"},
        [](const json& in, const json&) { return input_is(in, "pixels", "subnormal"); },
        "non-finite value (NaN, NaN, NaN, 5.96046448e-08)");
}

// negative_colour: every example is a covered pixel darker than the black level, alpha kept;
// the HDR input (no channel below 0.25) and the empty one (nothing covered) stay non-negative.
void negative_colour(const HarnessRun& run) {
    size_t examples = 0;
    for (const json* c : run.check_cases.at("non-negative")) {
        const json* check = HarnessRun::find_check(*c, "non-negative");
        for (const json& example : (*check)["examples"]) {
            const float a = number(example["input"][3]);
            EXPECT_GT(a, 0.0f) << example.dump();
            EXPECT_EQ(number(example["output"][3]), a) << example.dump();
            const float lowest =
                std::min({number(example["output"][0]), number(example["output"][1]),
                          number(example["output"][2])});
            EXPECT_LT(lowest, 0.0f) << example.dump();
            EXPECT_GE(lowest, -0.15f * a) << example.dump();
            ++examples;
        }
    }
    EXPECT_GT(examples, 0u);
    for (const char* id : {"inputs/hdr", "inputs/empty"}) {
        const json* c = run.find_case(id);
        ASSERT_NE(c, nullptr) << id;
        EXPECT_EQ((*c)["verdict"], "PASS") << c->dump(2);
    }
}

// build_leak: 256 KiB per build, two builds per load, over isolation/state's repeated loads.
void build_leak(const HarnessRun& run) {
    fails_only_where(
        run, "memory", {"isolation/state"}, [](const json&, const json&) { return true; },
        "loads of the same scene (allowance 2048 KiB): does build() leak?");
}

// result_partly_unwritten: where the input is transparent the output is the case's poison:
// NaN (finite) or a finite colour with alpha 0.75 or 0.5 (coverage), and two processes with
// different poisons differ (determinism).
void result_partly_unwritten(const HarnessRun& run) {
    for (const char* check : {"finite", "coverage"}) {
        size_t examples = 0;
        for (const json* c : run.check_cases.at(check)) {
            const json* k = HarnessRun::find_check(*c, check);
            if ((*k)["verdict"] != "FAIL") continue;
            EXPECT_EQ((*c)["inputs"]["poison"], check == std::string("finite") ? "nan" : "large")
                << (*c)["id"] << ": " << check;
            for (const json& example : (*k)["examples"]) {
                // The composite (floor -1) has no input to compare with.
                if (example["floor"].get<int64_t>() >= 0) {
                    EXPECT_EQ(number(example["input"][3]), 0.0f) << example.dump();
                }
                if (check == std::string("coverage")) {
                    EXPECT_EQ(number(example["output"][3]), 0.75f) << example.dump();
                }
                ++examples;
            }
        }
        EXPECT_GT(examples, 0u) << check;
    }
    const json* run2 = run.find_case("determinism/run-2");
    ASSERT_NE(run2, nullptr);
    const json* check = HarnessRun::find_check(*run2, "determinism");
    ASSERT_NE(check, nullptr);
    EXPECT_EQ((*check)["verdict"], "FAIL");
    EXPECT_TRUE(contains((*check)["message"].get<std::string>(), "their poisons differed"))
        << (*check)["message"];
}

// hidden_nan, inverted_smoothstep: finite as compiled, NaN with the checked built-ins, in both
// undefined cases (and no other case runs that check).
// hidden_nan, inverted_smoothstep: undefined wherever they run, so in every contract case
// (each renders once more with checked built-ins) that has coverage; each failure says what
// the pass gave as compiled. The cases of other kinds do not check undefined results.
void undefined_everywhere(const HarnessRun& run) {
    for (const char* id : {"contract/standard", "inputs/hdr", "sizes/odd", "lights/dark"}) {
        const json* c = run.find_case(id);
        ASSERT_NE(c, nullptr) << id;
        const json* check = HarnessRun::find_check(*c, "undefined-results");
        ASSERT_NE(check, nullptr) << id;
        EXPECT_EQ((*check)["verdict"], "FAIL") << id << ": " << check->dump(2);
    }
    for (const json* c : run.check_cases.at("undefined-results")) {
        const json* check = HarnessRun::find_check(*c, "undefined-results");
        if ((*check)["verdict"] != "FAIL") continue;
        EXPECT_TRUE(contains((*check)["message"].get<std::string>(), "; as compiled it gave ("))
            << (*c)["id"] << ": " << (*check)["message"];
    }
}

// undefined_at_max: undefined only where amount is above 0.5, which the defaults never are.
void undefined_away_from_defaults(const HarnessRun& run) {
    fails_only_where(
        run, "undefined-results", {"params/max", "params/sweep-amount"},
        [](const json&, const json& spec) {
            auto above = [](const json& params) { return params.value("amount", 0.0) > 0.5; };
            bool any = above(spec.value("params", json::object()));
            for (const json& point : spec.value("sweep", json::array())) any |= above(point);
            return any;
        },
        "; as compiled it gave (");
    const json* standard = run.find_case("contract/standard");
    ASSERT_NE(standard, nullptr);
    const json* check = HarnessRun::find_check(*standard, "undefined-results");
    ASSERT_NE(check, nullptr) << "contract/standard did not check undefined results";
    EXPECT_EQ((*check)["verdict"], "PASS") << check->dump(2);
}

// The edges of the format, one plugin each: each fails in its edge's own case only, or in a
// combined/* point that drew the same value.
void light_on_floor(const HarnessRun& run) {
    fails_only_where(run, "finite", {"lights/on-the-floor"}, [](const json& in, const json&) {
        return input_is(in, "lights", "on-the-floor");
    });
}
void sun_overhead(const HarnessRun& run) {
    fails_only_where(run, "finite", {"lights/zenith-sun"}, [](const json& in, const json&) {
        return input_is(in, "lights", "zenith-sun");
    });
}
void dark_light(const HarnessRun& run) {
    fails_only_where(run, "finite", {"lights/dark"},
                     [](const json& in, const json&) { return input_is(in, "lights", "dark"); });
}
void mask_over_one(const HarnessRun& run) {
    fails_only_where(run, "finite", {"masks/above-one"}, [](const json& in, const json&) {
        return input_is(in, "masks", "above-one");
    });
}
void ascii_floor_names(const HarnessRun& run) {
    fails_only_where(run, "non-negative", {"floors/unicode-names"},
                     [](const json& in, const json&) {
                         return input_is(in, "floor names and tiles", "unicode-names");
                     });
}
// empty_floor_bounds: SIGFPE in build() wherever the plugin is built for a floor without tiles.
void empty_floor_bounds(const HarnessRun& run) {
    size_t crashed = 0;
    for (const json& c : run.report["cases"]) {
        if (c["verdict"] != "CRASH") continue;
        ++crashed;
        EXPECT_TRUE(contains(c["message"].get<std::string>(), "SIGFPE")) << c.dump(2);
        EXPECT_TRUE(input_is(c["inputs"], "floor names and tiles", "top-floor-empty"))
            << c["id"] << " crashed without a floor without tiles: " << c["inputs"].dump();
    }
    const json* own = run.find_case("floors/top-floor-empty");
    ASSERT_NE(own, nullptr);
    EXPECT_EQ((*own)["verdict"], "CRASH") << own->dump(2);
    EXPECT_GE(crashed, 1u);
}

// fraction_below_one (a control): the case whose fraction would round up to 1 passes.
void fraction_below_one(const HarnessRun& run) {
    const json* c = run.find_case("time/fraction-rounds-up");
    ASSERT_NE(c, nullptr);
    EXPECT_EQ((*c)["verdict"], "PASS") << c->dump(2);
}

// clears_outside_coverage: alpha the spread put past the floor's tiles is erased, and only
// there: after the spread neighbour.
void clears_outside_coverage(const HarnessRun& run) {
    fails_only_where(
        run, "coverage", {"contexts/after-spread"},
        [](const json&, const json& spec) {
            return !spec.value("effects_before", json::array()).empty();
        },
        "alpha");
}
// canvas_fraction_falloff: fails the canvas-size relation, which only its own case runs.
void canvas_fraction_falloff(const HarnessRun& run) {
    fails_only_where(
        run, "canvas-size", {"relations/canvas-size"},
        [](const json&, const json& spec) { return spec.value("relation", "") == "canvas-size"; },
        "on the grown canvas");
}
// half_float_positions: rgba16f and rgba32f disagree, in the one case that compares them.
void half_float_positions(const HarnessRun& run) {
    fails_only_where(
        run, "format-agreement", {"formats/rgba32f"},
        [](const json&, const json& spec) { return spec.value("format", "") == "rgba32f"; },
        "in rgba16f");
}
// camera_blind: its light pool moves with the camera, in the one case that looks through one.
void camera_blind(const HarnessRun& run) {
    fails_only_where(
        run, "camera-region", {"relations/camera-region"},
        [](const json&, const json& spec) { return spec.value("relation", "") == "camera-region"; },
        "through the camera");
}
// scale_blind: its darkening reaches twice as far at scale 1/2, in the one case that renders
// at another scale; the message names the pixel at 1/2 and the declared tolerance.
void scale_blind(const HarnessRun& run) {
    fails_only_where(
        run, "camera-scale", {"relations/camera-scale"},
        [](const json&, const json& spec) { return spec.value("relation", "") == "camera-scale"; },
        "at 1/2 (pixel");
}

// declared_reach: the reach check runs (the plugin declares a reach) and passes everywhere.
void reach_checked(const HarnessRun& run) {
    ASSERT_TRUE(run.check_cases.count("reach")) << "the reach check never ran";
    EXPECT_FALSE(run.check_cases.at("reach").empty());
}

// short_reach: where a floor does not cover the canvas, its glow past 1 pixel is cut off; the
// failure says what the floor is when shaded over the whole canvas.
void reach_cut_off(const HarnessRun& run) {
    bool named = false;
    for (const json* c : run.check_cases.at("reach")) {
        const json* check = HarnessRun::find_check(*c, "reach");
        if (check && (*check)["verdict"] == "FAIL")
            named |= (*check)["message"].get<std::string>().find(
                         "changed past the declared reach") != std::string::npos;
    }
    EXPECT_TRUE(named);
}

}  // namespace acetate::battery
