// The contract cases (each output against its input) and the disconnected-parameter case.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "case_kinds.hpp"
#include "input_model.hpp"
#include "relation_checks.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

Result<CheckResult> check_reach(const CaseContext& c, Session& s, CaseWriter& w, const json& params,
                                const std::string& name, const std::vector<FloorImages>& clipped,
                                std::map<int64_t, ImageRGBA>& heat);

Result<CheckResult> check_undefined(const CaseContext& c, Session& s, CaseWriter& w,
                                    const json& params, const std::string& name,
                                    EffectPassCounts passes, const std::vector<FloorImages>& plain,
                                    std::map<int64_t, ImageRGBA>& heat);

// One scene of the case in a load of its own: the earlier frames, then each floor that
// carries the plugin (or the composite) before and after the effects, checked. Returns the
// checks with their heat maps; none when the load failed (recorded by load_layout).
struct SceneChecks {
    std::vector<CheckResult> checks;
    std::map<std::string, std::map<int64_t, ImageRGBA>> heat;
};
Result<std::optional<SceneChecks>> check_scene(const CaseContext& c, Session& s, CaseWriter& w,
                                               const json& params, const std::string& name,
                                               bool pictures) {
    auto comp = load_layout(c, s, w, case_layout(c, params), name);
    if (!comp) return comp.error();
    if (!*comp) return std::optional<SceneChecks>();
    ACETATE_TRY(render_earlier_frames(**comp, c));
    std::vector<Capture> captures;
    std::vector<int64_t> floor_of;
    // The plugin's own input and output (between its neighbours, in a context case).
    if (c.plugin.is_global()) {
        auto capture = capture_plugin(**comp, c, c.spec.floors - 1);
        if (!capture) return capture.error();
        captures.push_back(std::move(capture.value()));
        floor_of.push_back(-1);
    } else {
        for (uint32_t f : plugin_floors(c)) {
            auto capture = capture_plugin(**comp, c, f);
            if (!capture) return capture.error();
            captures.push_back(std::move(capture.value()));
            floor_of.push_back(f);
        }
    }
    std::vector<FloorImages> floors;
    for (size_t i = 0; i < captures.size(); ++i) {
        floors.push_back({floor_of[i], &captures[i].input, &captures[i].output});
        const std::string suffix =
            floor_of[i] >= 0 ? fmt::format("floor{}", floor_of[i]) : "composite";
        if (pictures) {
            w.case_picture("input." + suffix, captures[i].input);
            w.case_picture("output." + suffix, captures[i].output);
        }
    }
    // NaN/Inf anywhere: the composite of every floor with all effects on, too.
    ACETATE_TRY((**comp).render(c.spec.floors - 1, c.spec.time));
    auto composite = (**comp).read_accumulation();
    if (!composite) return composite.error();
    if (pictures) w.case_picture("composite", *composite);
    SceneChecks out;
    out.checks = check_contract(floors, c.plugin.is_expanding(), &out.heat,
                                {{-1, nullptr, &composite.value()}});
    {
        auto undefined = check_undefined(c, s, w, params, name, (**comp).effect_pass_counts(),
                                         floors, out.heat["undefined-results"]);
        if (!undefined) return undefined.error();
        out.checks.push_back(std::move(undefined.value()));
    }
    if (c.spec.relation != Relation::None) {
        auto relation =
            check_relation(c, s, w, params, name, floors, out.heat[to_string(c.spec.relation)]);
        if (!relation) return relation.error();
        out.checks.push_back(std::move(relation.value()));
    }
    // Only an expanding plugin declares a reach: one a neighbour declared is not the plugin's.
    if (!c.plugin.is_global() && c.plugin.is_expanding() && (**comp).declares_reach()) {
        auto reach = check_reach(c, s, w, params, name, floors, out.heat["reach"]);
        if (!reach) return reach.error();
        out.checks.push_back(std::move(reach.value()));
    }
    return std::optional<SceneChecks>(std::move(out));
}

// An expanding floor effect that declared a reach (set_reach) is shaded only within its
// floor's tiles grown by that reach. The same scene shaded over the whole canvas must give the
// same floor, bit for bit: a difference is a pixel the effect changes past its declared reach,
// which the host would silently cut off.
Result<CheckResult> check_reach(const CaseContext& c, Session& s, CaseWriter& w, const json& params,
                                const std::string& name, const std::vector<FloorImages>& clipped,
                                std::map<int64_t, ImageRGBA>& heat) {
    CheckAccumulator reach("reach",
                           "nothing changes past the declared reach (same floor when shaded over "
                           "the whole canvas)");
    LoadOptions how;
    how.ignore_declared_reach = true;
    auto comp = load_layout(c, s, w, case_layout(c, params), name + ".unclipped", how);
    if (!comp) return comp.error();
    if (!*comp) return reach.finish();  // the load failure is recorded already
    ACETATE_TRY(render_earlier_frames(**comp, c));
    for (const FloorImages& floor : clipped) {
        auto capture = capture_plugin(**comp, c, uint32_t(floor.floor));
        if (!capture) return capture.error();
        const ImageRGBA& whole = capture->output;
        for (uint32_t y = 0; y < whole.height; ++y)
            for (uint32_t x = 0; x < whole.width; ++x)
                if (std::memcmp(whole.at(x, y), floor.output->at(x, y), 4 * sizeof(float)) != 0) {
                    const float* v = whole.at(x, y);
                    reach.violation(floor, x, y,
                                    fmt::format("shaded over the whole canvas it is ({}, {}, {}, "
                                                "{}): changed past the declared reach",
                                                v[0], v[1], v[2], v[3]));
                }
    }
    heat = reach.heat_maps();
    return reach.finish();
}

// The scene once more with the plugin's GLSL compiled with checked min, max, clamp,
// smoothstep and texelFetch, which give NaN for a NaN operand, inverted edges or a texel
// outside the texture (the same earlier frames, time and floors). A pixel finite as compiled
// (`plain`) and not finite when checked is a result the GLSL leaves undefined: llvmpipe launders a
// NaN through min/max/clamp into a finite value, another driver may not.
Result<CheckResult> check_undefined(const CaseContext& c, Session& s, CaseWriter& w,
                                    const json& params, const std::string& name,
                                    EffectPassCounts passes, const std::vector<FloorImages>& plain,
                                    std::map<int64_t, ImageRGBA>& heat) {
    CheckAccumulator undefined(
        "undefined-results",
        fmt::format("no NaN operand of min, max or clamp, no smoothstep with edge0 >= edge1 "
                    "and no texelFetch outside its texture in the {} GLSL pass{}{}",
                    passes.glsl, passes.glsl == 1 ? "" : "es",
                    passes.spirv ? fmt::format("; {} pass{} given as SPIR-V could not be checked",
                                               passes.spirv, passes.spirv == 1 ? "" : "es")
                                 : ""));
    if (passes.glsl == 0 && passes.spirv == 0) {
        CheckResult result = undefined.finish();
        result.message = "no pass to check: the plugin declared none for this scene's floors";
        return result;
    }
    if (passes.glsl == 0) {
        CheckResult result = undefined.finish();
        result.verdict = Verdict::Skip;
        result.message = fmt::format(
            "not judged: every one of the {} passes was given as SPIR-V, which the harness cannot "
            "recompile with checked built-ins",
            passes.spirv);
        return result;
    }
    LoadOptions how;
    how.checked_builtins = true;
    auto comp = load_layout(c, s, w, case_layout(c, params), name + ".checked", how);
    if (!comp) return comp.error();
    if (!*comp) return undefined.finish();  // the load failure is recorded already
    ACETATE_TRY(render_earlier_frames(**comp, c));
    for (const FloorImages& floor : plain) {
        const bool global = floor.floor < 0;
        auto checked =
            plugin_own_output(**comp, c, global ? c.spec.floors - 1 : uint32_t(floor.floor));
        if (!checked) return checked.error();
        const ImageRGBA& as_compiled = *floor.output;
        const FloorImages where{floor.floor, &as_compiled, &checked.value()};
        for (uint32_t y = 0; y < as_compiled.height; ++y)
            for (uint32_t x = 0; x < as_compiled.width; ++x) {
                const float *a = as_compiled.at(x, y), *b = checked->at(x, y);
                const bool finite_before =
                    std::all_of(a, a + 4, [](float v) { return std::isfinite(v); });
                const bool finite_after =
                    std::all_of(b, b + 4, [](float v) { return std::isfinite(v); });
                if (finite_before && !finite_after)
                    undefined.violation(
                        where, x, y,
                        fmt::format("{} here only because min, max, clamp or smoothstep was "
                                    "given a NaN or inverted edges, or texelFetch read outside "
                                    "its texture; as compiled it gave {}",
                                    format_rgba(b), format_rgba(a)));
            }
    }
    heat = undefined.heat_maps();
    return undefined.finish();
}

bool any_failing(const std::vector<CheckResult>& checks) {
    return std::any_of(checks.begin(), checks.end(),
                       [](const CheckResult& check) { return is_failing(check.verdict); });
}

}  // namespace

// Renders the plugin's floors (or the composite) and checks each against its input: once, or
// once per value of a sweep, each in a load of its own, stopping at the first that fails.
Result<void> run_contract(const CaseContext& c, Session& s, CaseWriter& w) {
    auto history = render_history(c, s, w);
    if (!history) return history.error();
    if (!*history) return {};
    if (c.spec.sweep.empty()) {
        auto scene = check_scene(c, s, w, c.spec.params, "scene", true);
        if (!scene) return scene.error();
        if (*scene) w.add_all(std::move((*scene)->checks), (*scene)->heat);
        return {};
    }
    for (size_t i = 0; i < c.spec.sweep.size(); ++i) {
        json params = c.spec.params;
        params.update(c.spec.sweep[i]);
        const bool final_value = i + 1 == c.spec.sweep.size();
        // Pictures of every value, each overwriting the last: the report shows the failing
        // value, or the last one.
        auto scene = check_scene(c, s, w, params, fmt::format("sweep{}", i), true);
        if (!scene) return scene.error();
        if (!*scene) return {};
        const bool failed = any_failing((*scene)->checks);
        if (!failed && !final_value) continue;
        for (CheckResult& check : (*scene)->checks)
            check.message =
                failed && is_failing(check.verdict)
                    ? fmt::format("at {}: {}", c.spec.sweep[i].dump(), check.message)
                    : fmt::format("{} ({} values swept)", check.message, c.spec.sweep.size());
        w.add_all(std::move((*scene)->checks), (*scene)->heat);
        return {};
    }
    return {};
}

// Each parameter at its minimum and at its maximum, on a scene with lights and every mask
// kind the plugin reads, at three times, with the other parameters at their defaults, then all
// at their minimums, then all at their maximums (a parameter may matter only when another
// allows it, like a night level by day): identical outputs throughout mean the parameter is
// not connected to anything (docs/design.md, L-connected).
Result<void> run_disconnected(const CaseContext& c, Session& s, CaseWriter& w) {
    constexpr float kTimes[] = {0.0f, 0.37f, 1.9f};
    // Each parameter at its two ends first, then, only when they give the same output, at
    // interior points: a periodic parameter (an azimuth of 0..360) has equal ends and is
    // connected all the same. Connected when any two of its values differ.
    constexpr int kPoints = 5;
    enum class Others { Default, Min, Max };
    std::vector<std::string> disconnected, periodic;
    for (const ParamInfo& p : c.plugin.params) {
        if (p.min_value == p.max_value) continue;
        std::vector<float> values = sweep_values(p, kPoints);
        std::rotate(values.begin() + 1, values.end() - 1, values.end());  // min, max, interior
        bool connected = false;
        for (Others others : {Others::Default, Others::Min, Others::Max}) {
            std::vector<std::string> first;
            for (size_t i = 0; i < values.size() && !connected; ++i) {
                json params = json::object();
                for (const ParamInfo& q : c.plugin.params)
                    if (others != Others::Default)
                        params[q.name] = others == Others::Min ? q.min_value : q.max_value;
                params[p.name] = values[i];
                const std::string name = fmt::format("{}.{:g}", p.name, values[i]);
                auto comp = load_layout(c, s, w, case_layout(c, params), name);
                if (!comp) return comp.error();
                if (!*comp) return {};
                std::vector<std::string> digests;
                for (float t : kTimes) {
                    ACETATE_TRY((**comp).render(c.spec.floors - 1, t));
                    auto image = c.plugin.is_global() ? (**comp).read_accumulation()
                                                      : (**comp).read_active_floor();
                    if (!image) return image.error();
                    digests.push_back(digest_images({&image.value()}));
                }
                if (i == 0)
                    first = std::move(digests);
                else if (digests != first)
                    connected = true;
                if (connected && i >= 2) periodic.push_back(p.name);
            }
            if (connected) break;
        }
        if (!connected) disconnected.push_back(p.name);
    }
    CheckResult check;
    check.check = "disconnected-parameters";
    if (disconnected.empty()) {
        check.message = fmt::format("each of the {} parameters changed the output over its range",
                                    c.plugin.params.size());
        if (!periodic.empty())
            check.message += fmt::format(
                " ({} only between interior values: its minimum and maximum give the same "
                "output, as a periodic parameter's do)",
                fmt::join(periodic, ", "));
    } else {
        check.verdict = Verdict::Fail;
        check.violations = disconnected.size();
        check.message = fmt::format(
            "parameter{} {} changed nothing over {} values from minimum to maximum ({}x{} scene "
            "with 3 lights{}, times 0, 0.37 and 1.9, the other parameters at default, minimum "
            "and maximum): not connected to the shader?",
            disconnected.size() == 1 ? "" : "s", fmt::join(disconnected, ", "), kPoints,
            c.spec.width, c.spec.height,
            c.plugin.masks.empty() ? ""
                                   : fmt::format(" and masks {}", fmt::join(c.plugin.masks, ", ")));
    }
    w.add(check);
    return {};
}

void plan_disconnected(const PlanContext& context, Planner& p) {
    if (context.plugin.params.empty()) return;
    CaseSpec s = p.contract("params/disconnected",
                            "each parameter at its minimum and maximum must change the "
                            "output (lights, masks and three times given)");
    s.kind = CaseKind::Disconnected;
    p.add(s);
}

}  // namespace acetate::harness
