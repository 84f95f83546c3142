// The contract kind's plan: which contract cases a run has (docs/harness.md, "The cases").
// Every dimension of the input model (input_model.hpp) is varied on its own at least once, at
// every strictness; the contexts and relations; the combinations. The sweep points, frames and
// combined cases grow with strictness.
#include <fmt/format.h>

#include <algorithm>

#include "case_kinds.hpp"
#include "case_spec.hpp"
#include "combinations.hpp"
#include "input_model.hpp"
#include "neighbours.hpp"
#include "references.hpp"

namespace acetate::harness {
namespace {

using nlohmann::json;

json all_params_at(const PluginInfo& plugin, bool at_max) {
    json params = json::object();
    for (const ParamInfo& p : plugin.params) params[p.name] = at_max ? p.max_value : p.min_value;
    return params;
}

}  // namespace

void plan_contract(const PlanContext& context, Planner& p) {
    const PluginInfo& plugin = context.plugin;
    const int strictness = context.strictness;
    const uint64_t run_seed = context.run_seed;
    const bool floor_effect = context.floor_effect();
    // ---- canvas ----
    p.add(p.contract("contract/standard", "one floor: opaque, partial and transparent areas", 256,
                     160));
    p.add(p.contract("contract/three-floors",
                     "three overlapping floors, each with its own coverage and lights", 256, 160,
                     Pattern::Standard, 3));
    p.add(p.contract("sizes/1x1", "a 1x1 canvas", 1, 1));
    p.add(p.contract("sizes/odd", "an odd size, 37x23", 37, 23));
    p.add(p.contract("sizes/odd-even", "odd width, even height: 37x24", 37, 24));
    p.add(p.contract("sizes/even-odd", "even width, odd height: 38x23", 38, 23));
    p.add(p.contract("sizes/thin", "a one-pixel-high strip, 333x1", 333, 1));
    if (strictness >= 7) p.add(p.contract("sizes/tall", "a one-pixel-wide strip, 1x517", 1, 517));
    const uint32_t large_w = strictness <= 3 ? 1024 : strictness <= 7 ? 1920 : 4096;
    const uint32_t large_h = strictness <= 3 ? 768 : strictness <= 7 ? 1080 : 2304;
    p.add(p.contract("sizes/large", fmt::format("a large canvas, {}x{}", large_w, large_h), large_w,
                     large_h));

    // ---- pixels ----
    p.add(p.contract("inputs/hdr", "HDR values up to the half-float maximum 65504", 128, 96,
                     Pattern::Hdr));
    p.add(p.contract("inputs/alpha-ramp", "alpha from 1 down to 1/65535 across the canvas", 256, 64,
                     Pattern::AlphaRamp));
    p.add(p.contract("inputs/subnormal",
                     "alpha at the smallest half-float subnormal 2^-24 and other tiny values, "
                     "under colour up to 1000 times alpha",
                     96, 64, Pattern::Subnormal));
    p.add(p.contract("inputs/empty", "a floor whose tile is fully transparent", 96, 64,
                     Pattern::Empty));
    p.add(
        p.contract("inputs/opaque", "a floor that is opaque everywhere", 96, 64, Pattern::Opaque));

    // ---- floors and the floor the plugin is on ----
    if (floor_effect) {
        CaseSpec s = p.contract("floors/one-of-two", "two floors, the plugin on floor 1 only", 128,
                                96, Pattern::Standard, 2);
        s.plugin_floor = 1;
        p.add(s);
        s = p.contract("floors/top-of-five", "five floors, the plugin on floor 4 only", 128, 96,
                       Pattern::Standard, 5);
        s.plugin_floor = 4;
        p.add(s);
    }
    p.add(p.contract("floors/eight", "eight floors, the plugin on every one (or the composite)",
                     128, 96, Pattern::Standard, 8));
    p.add(p.contract("sizes/wide-floors", "three floors on a wide canvas, 2048x40", 2048, 40,
                     Pattern::Standard, 3));
    // ---- the floors' names and tiles ----
    const std::pair<FloorVariant, const char*> floor_variants[] = {
        {FloorVariant::LongNames, "floors named with 300 characters"},
        {FloorVariant::UnicodeNames, "floors named outside ASCII (UTF-8: accents, CJK, an emoji)"},
        {FloorVariant::TopFloorEmpty, "the top floor of two has no tile at all"},
    };
    for (const auto& [variant, what] : floor_variants) {
        CaseSpec s = p.contract(std::string("floors/") + to_string(variant), what, 96, 64,
                                Pattern::Standard, 2);
        s.floor_variant = variant;
        p.add(s);
    }

    // ---- lights (a global effect sees none) ----
    if (floor_effect) {
        const std::pair<LightSet, const char*> light_cases[] = {
            {LightSet::None, "no lights"},
            {LightSet::One, "one light at the centre"},
            {LightSet::Many, "100 lights, more than any preset's cap"},
            {LightSet::OffCanvas, "three lights off the canvas, reaching onto it"},
            {LightSet::Tiny, "three lights with a radius of 10^-4 pixels"},
            {LightSet::Huge, "three lights with a radius of 10^6 pixels"},
            {LightSet::Sun, "three lights at several heights and a sun at 40 degrees"},
            {LightSet::GrazingSun, "one light and a sun on the horizon (elevation 0)"},
            {LightSet::ZenithSun, "one light and a sun overhead (elevation 90, azimuth -360)"},
            {LightSet::OnTheFloor,
             "three lights at height exactly 0 on whole-pixel corners: (0, 0), the canvas's "
             "bottom-right corner and its centre"},
            {LightSet::Dark, "lights and a sun of colour 0 or intensity 0"},
        };
        for (const auto& [lights, what] : light_cases) {
            CaseSpec s = p.contract(std::string("lights/") + to_string(lights), what);
            s.lights = lights;
            p.add(s);
        }
    }

    // ---- masks (only the kinds the plugin reads) ----
    if (!plugin.masks.empty()) {
        const std::pair<MaskFill, const char*> mask_cases[] = {
            {MaskFill::Absent, "tiles carry no mask: the host's transparent texture"},
            {MaskFill::Empty, "every mask 0"},
            {MaskFill::Full, "every mask 1"},
            {MaskFill::Partial, "masks on half of the tile, 0 on the other half"},
            {MaskFill::AboveOne, "masks from 1 to 4 (data: the format does not bound them)"},
            {MaskFill::Thin, "one-pixel lines of 1 on 0, along the tile's edges and through it"},
        };
        for (const auto& [masks, what] : mask_cases) {
            CaseSpec s = p.contract(std::string("masks/") + to_string(masks), what);
            s.masks = masks;
            p.add(s);
        }
    }

    // ---- parameters: ends, presets, each swept over its range ----
    if (!plugin.params.empty()) {
        CaseSpec s = p.contract("params/min", "every parameter at its minimum");
        s.params = all_params_at(plugin, false);
        s.inputs["params"] = "all at minimum";
        p.add(s);
        s = p.contract("params/max", "every parameter at its maximum");
        s.params = all_params_at(plugin, true);
        s.inputs["params"] = "all at maximum";
        p.add(s);
    }
    for (const std::string& preset : plugin.presets) {
        CaseSpec s = p.contract("params/preset-" + preset, "preset \"" + preset + "\"");
        s.preset = preset;
        p.add(s);
        if (plugin.params.empty()) continue;
        // The scene's values override the preset's: every parameter at its maximum over it.
        s = p.contract("params/preset-" + preset + "-overridden",
                       "preset \"" + preset + "\" with every parameter set to its maximum");
        s.preset = preset;
        s.params = all_params_at(plugin, true);
        s.inputs["params"] = "preset " + preset + ", all overridden at maximum";
        p.add(s);
    }
    const int sweep_points = 3 + strictness;  // 8 at the default strictness
    for (const ParamInfo& param : plugin.params) {
        if (param.min_value == param.max_value) continue;
        const std::vector<float> values = sweep_values(param, sweep_points);
        CaseSpec s =
            p.contract("params/sweep-" + param.name,
                       fmt::format("{} at {} values from {:g} to {:g}, the others at default, "
                                   "one load each",
                                   param.name, values.size(), values.front(), values.back()));
        for (float v : values) s.sweep.push_back(json{{param.name, v}});
        s.inputs["params"] = fmt::format("sweep of {}", param.name);
        p.add(s);
    }

    // ---- time, frames, loads ----
    // 2.99999999 s: its fraction, 0.99999999, rounds up to 1.0 as a float.
    const std::pair<double, const char*> times[] = {{0.37, "fractional"},
                                                    {-2.5, "negative"},
                                                    {1.0e5, "large"},
                                                    {2.99999999, "fraction-rounds-up"}};
    for (const auto& [time, name] : times) {
        CaseSpec s = p.contract(std::string("time/") + name, fmt::format("time {:.9g} s", time));
        s.time = time;
        p.add(s);
    }
    CaseSpec frames =
        p.contract("frames/many", "many frames in one load at advancing times; the last checked");
    frames.frames = 8 + 2 * uint32_t(strictness);
    frames.time = 1.0f;
    p.add(frames);
    CaseSpec loads = p.contract("loads/after-others",
                                "two other scenes (other canvases and floors) loaded "
                                "and rendered in the process first");
    loads.prior_loads = 2;
    p.add(loads);

    // ---- contexts: the harness's spread neighbour before and after the plugin; rgba32f ----
    // The spread puts alpha past the floor's tiles (and its coverage bounds), which the plugin
    // after it is given and must keep; the plugin before it must hand on a valid image.
    const std::string spread = spread_neighbour_id(!floor_effect);
    for (const bool before : {false, true}) {
        CaseSpec s = p.contract(
            before ? "contexts/before-spread" : "contexts/after-spread",
            before ? "the plugin before the harness's coverage-expanding spread neighbour"
                   : "the plugin after the harness's coverage-expanding spread neighbour, which "
                     "puts alpha past the floor's tiles",
            128, 96, Pattern::Standard, 2);
        (before ? s.effects_after : s.effects_before).push_back(spread);
        p.add(s);
    }
    {
        // Wider than 2048: past it a half float cannot hold every pixel position.
        CaseSpec s = p.contract("formats/rgba32f",
                                "rgba32f targets on a canvas wider than 2048, 2560x40, two "
                                "floors; against the same scene in rgba16f",
                                2560, 40, Pattern::Standard, 2);
        s.format = TargetFormat::Rgba32f;
        s.relation = Relation::FormatAgreement;
        p.add(s);
    }
    // The relations a floor effect is held to, each on two floors of the standard tile.
    struct RelationCase {
        const char* id;
        const char* description;
        Relation relation;
    };
    constexpr RelationCase kFloorRelations[] = {
        {"relations/camera-region",
         "two floors, transparent along every edge, against the same floors through a camera "
         "whose region starts left of and above the canvas (ABI 1.2)",
         Relation::CameraRegion},
        {"relations/camera-scale",
         "two floors against the same floors through a camera over the whole canvas at scale "
         "1/2 (ABI 1.2)",
         Relation::CameraScale},
        {"relations/canvas-size",
         "two floors, transparent along the right and bottom edges, against the same floors on "
         "a larger canvas",
         Relation::CanvasSize}};
    for (const RelationCase& r : kFloorRelations) {
        if (!floor_effect) break;
        CaseSpec s = p.contract(r.id, r.description, 128, 96, Pattern::Standard, 2);
        s.relation = r.relation;
        p.add(s);
    }

    // ---- combinations: pairwise from strictness 4, Latin hypercube points below it and
    // from strictness 6 on top of it ----
    if (strictness >= kPairwiseStrictness)
        for (CaseSpec& s : pairwise_combinations(plugin, run_seed).cases) p.add(std::move(s));
    if (strictness < kPairwiseStrictness || strictness >= 6) {
        const size_t points = size_t(2 * strictness);
        const auto design =
            latin_hypercube(points, scenario_dimensions(plugin), case_seed(run_seed, "combined"));
        for (size_t i = 0; i < points; ++i) {
            CaseSpec s = p.contract(fmt::format("combined/{}", i + 1),
                                    "a point of the Latin hypercube over every input dimension");
            scenario_at(plugin, design[i], s);
            s.inputs["params"] = "Latin hypercube";
            p.add(s);
        }
    }
}

std::string combinations_summary(const PluginInfo& plugin, int strictness, uint64_t run_seed) {
    strictness = std::clamp(strictness, 1, 10);
    const std::string hypercube =
        fmt::format("{} points of a Latin hypercube over every dimension", 2 * strictness);
    if (strictness < kPairwiseStrictness)
        return hypercube +
               fmt::format(" (strength 1; pairwise from strictness {})", kPairwiseStrictness);
    const std::string pairwise = pairwise_combinations(plugin, run_seed).summary;
    return strictness >= 6 ? pairwise + ", and " + hypercube : pairwise;
}

}  // namespace acetate::harness
