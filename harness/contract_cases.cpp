// The contract cases (each output against its input) and the disconnected-parameter case.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "case_kinds.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

Result<CheckResult> check_reach(const CaseContext& c, Session& s, CaseWriter& w, const json& params,
                                const std::string& name, const std::vector<FloorImages>& clipped,
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
    if (c.plugin.is_global()) {
        auto capture = capture_global(**comp, c.spec.floors - 1, c.spec.time);
        if (!capture) return capture.error();
        captures.push_back(std::move(capture.value()));
        floor_of.push_back(-1);
    } else {
        for (uint32_t f : plugin_floors(c)) {
            auto capture = capture_floor(**comp, f, c.spec.time);
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
    if (!c.plugin.is_global() && (**comp).declares_reach()) {
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
        auto capture = capture_floor(**comp, uint32_t(floor.floor), c.spec.time);
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
                auto comp = load_layout(c, s, w, case_layout(c, params), name);
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

// The scene twice: as compiled normally, and with the plugin's GLSL compiled with checked
// min, max, clamp and smoothstep that give NaN for a NaN operand or inverted edges. A pixel
// finite in the first and not in the second is a result the GLSL leaves undefined: llvmpipe
// launders a NaN through min/max/clamp into a finite value, another driver may not.
Result<void> run_undefined(const CaseContext& c, Session& s, CaseWriter& w) {
    const bool global = c.plugin.is_global();
    std::vector<uint32_t> floors = plugin_floors(c);
    if (global) floors = {c.spec.floors - 1};
    std::vector<ImageRGBA> outputs[2];
    EffectPassCounts passes;
    for (int checked = 0; checked < 2; ++checked) {
        auto comp = load_layout(c, s, w, case_layout(c), checked ? "checked" : "scene",
                                LoadOptions{checked == 1});
        if (!comp) return comp.error();
        if (!*comp) return {};
        passes = (**comp).effect_pass_counts();
        for (uint32_t f : floors) {
            auto out = plugin_output(**comp, global, f, c.spec.time);
            if (!out) return out.error();
            outputs[checked].push_back(std::move(out.value()));
        }
    }
    CheckAccumulator undefined(
        "undefined-results",
        fmt::format("no NaN operand of min, max or clamp and no smoothstep with edge0 >= edge1 "
                    "in the {} GLSL pass{}{}",
                    passes.glsl, passes.glsl == 1 ? "" : "es",
                    passes.spirv ? fmt::format("; {} pass{} given as SPIR-V could not be checked",
                                               passes.spirv, passes.spirv == 1 ? "" : "es")
                                 : ""));
    for (size_t i = 0; i < floors.size(); ++i) {
        const ImageRGBA &plain = outputs[0][i], &checked = outputs[1][i];
        const FloorImages where{global ? -1 : int64_t(floors[i]), &plain, &checked};
        for (uint32_t y = 0; y < plain.height; ++y)
            for (uint32_t x = 0; x < plain.width; ++x) {
                const float *a = plain.at(x, y), *b = checked.at(x, y);
                const bool finite_before =
                    std::all_of(a, a + 4, [](float v) { return std::isfinite(v); });
                const bool finite_after =
                    std::all_of(b, b + 4, [](float v) { return std::isfinite(v); });
                if (finite_before && !finite_after)
                    undefined.violation(
                        where, x, y,
                        fmt::format("{} here only because min, max, clamp or smoothstep was "
                                    "given a NaN or inverted edges; as compiled it gave {}",
                                    format_rgba(b), format_rgba(a)));
            }
    }
    CheckResult result = undefined.finish();
    if (passes.glsl == 0 && passes.spirv > 0) {
        result.verdict = Verdict::Skip;
        result.message = fmt::format(
            "not judged: every one of the {} passes was given as SPIR-V, which the harness cannot "
            "recompile with checked built-ins",
            passes.spirv);
    }
    w.add(std::move(result), &undefined.heat_maps());
    return {};
}

}  // namespace acetate::harness
