#include "relation_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace acetate::harness {

using nlohmann::json;

float half_ulp(float v) {
    const float a = std::fabs(v);
    if (!(a >= 0x1p-14f)) return 0x1p-24f;  // subnormal halves are 2^-24 apart
    int exponent = 0;
    std::frexp(a, &exponent);                // a = m * 2^exponent, m in [0.5, 1)
    return std::ldexp(1.0f, exponent - 11);  // 10 fraction bits after the leading one
}

namespace {

// The plugin's outputs, floor by floor as `floors` lists them, in a scene loaded from `layout`.
Result<std::optional<std::vector<ImageRGBA>>> outputs_in(const CaseContext& c, Session& s,
                                                         CaseWriter& w, const SceneLayout& layout,
                                                         const std::string& name,
                                                         const std::vector<FloorImages>& floors,
                                                         const LoadOptions& how) {
    auto comp = load_layout(c, s, w, layout, name, how);
    if (!comp) return comp.error();
    if (!*comp) return std::optional<std::vector<ImageRGBA>>();
    ACETATE_TRY(render_earlier_frames(**comp, c));
    std::vector<ImageRGBA> out;
    for (const FloorImages& floor : floors) {
        auto image = plugin_own_output(**comp, c,
                                       floor.floor < 0 ? c.spec.floors - 1 : uint32_t(floor.floor));
        if (!image) return image.error();
        out.push_back(std::move(image.value()));
    }
    return std::optional(std::move(out));
}

// Every pixel of `a` (the case's output) whose channel differs from `b`'s by more than
// `tolerance(value)` is a violation, `b` read at the same scene pixel.
template <class Tolerance>
void compare_within(const FloorImages& floor, const ImageRGBA& b, Tolerance tolerance,
                    const std::string& other, CheckAccumulator& out) {
    const ImageRGBA& a = *floor.output;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x) {
            const float *p = a.at(x, y), *q = b.at(x, y);
            for (int k = 0; k < 4; ++k) {
                if (std::isnan(p[k]) || std::isnan(q[k])) continue;  // `finite` says so
                const float bound = tolerance(std::max(std::fabs(p[k]), std::fabs(q[k])));
                if (!(std::fabs(p[k] - q[k]) <= bound)) {
                    out.violation(floor, x, y,
                                  fmt::format("{} here, {} {}: more than {:g} apart in a channel",
                                              format_rgba(p), format_rgba(q), other, bound));
                    break;
                }
            }
        }
}

Result<CheckResult> canvas_size(const CaseContext& c, Session& s, CaseWriter& w, const json& params,
                                const std::string& name, const std::vector<FloorImages>& floors,
                                std::map<int64_t, ImageRGBA>& heat) {
    SceneLayout grown = case_layout(c, params);
    grown.width += kCanvasGrowth[0];
    grown.height += kCanvasGrowth[1];
    CheckAccumulator relation(
        "canvas-size",
        fmt::format("the same floors on a canvas grown to {}x{} give the same pixels on the "
                    "original {}x{} (within one half-float unit)",
                    grown.width, grown.height, c.spec.width, c.spec.height));
    auto large = outputs_in(c, s, w, grown, name + ".grown", floors, {});
    if (!large) return large.error();
    if (!*large) return relation.finish();  // the load failure is recorded already
    for (size_t i = 0; i < floors.size(); ++i) {
        // Why one unit: a sampling position normalized by the canvas size rounds differently
        // on another canvas (float32), which can move an output rounded to half by one unit.
        ImageRGBA& g = (**large)[i];
        ImageRGBA cropped(c.spec.width, c.spec.height);
        for (uint32_t y = 0; y < c.spec.height; ++y)
            std::copy_n(g.at(0, y), 4 * c.spec.width, cropped.at(0, y));
        compare_within(floors[i], cropped, half_ulp, "on the grown canvas", relation);
    }
    heat = relation.heat_maps();
    return relation.finish();
}

Result<CheckResult> format_agreement(const CaseContext& c, Session& s, CaseWriter& w,
                                     const json& params, const std::string& name,
                                     const std::vector<FloorImages>& floors,
                                     std::map<int64_t, ImageRGBA>& heat) {
    // The case runs in rgba32f; its inputs are rounded to half, so both formats start alike.
    CheckAccumulator relation(
        "format-agreement",
        fmt::format("rgba32f and rgba16f agree within {} half-float units", kFormatAgreementUnits));
    LoadOptions how;
    how.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    auto half = outputs_in(c, s, w, case_layout(c, params), name + ".rgba16f", floors, how);
    if (!half) return half.error();
    if (!*half) return relation.finish();
    for (size_t i = 0; i < floors.size(); ++i) {
        // Why relative to the input's largest value: a target of the floor's format rounds each
        // value to 2^-11 of its size, and an effect that combines pixels (a blur, a pyramid)
        // carries the rounding of the largest values it combines into its small outputs.
        float largest = 0;
        for (float v : floors[i].input->pixels)
            if (std::isfinite(v)) largest = std::max(largest, std::fabs(v));
        compare_within(
            floors[i], (**half)[i],
            [largest](float v) { return kFormatAgreementUnits * half_ulp(std::max(v, largest)); },
            "in rgba16f", relation);
    }
    heat = relation.heat_maps();
    return relation.finish();
}

// A plugin built before the camera renders only without one: hosts refuse any other.
std::optional<CheckResult> camera_unjudged(const CaseContext& c, const char* check) {
    if (c.plugin.abi != "1.0" && c.plugin.abi != "1.1") return std::nullopt;
    CheckResult skipped;
    skipped.check = check;
    skipped.verdict = Verdict::Skip;
    skipped.message = fmt::format(
        "not judged: built against ABI {}, which has no camera (hosts refuse one)", c.plugin.abi);
    return skipped;
}

Result<CheckResult> camera_region(const CaseContext& c, Session& s, CaseWriter& w,
                                  const json& params, const std::string& name,
                                  const std::vector<FloorImages>& floors,
                                  std::map<int64_t, ImageRGBA>& heat) {
    const uint32_t dx = kCameraShift[0], dy = kCameraShift[1];
    CheckAccumulator relation(
        "camera-region",
        fmt::format("the same floors through a camera whose region starts {} and {} pixels left "
                    "of and above the canvas give the same pixels where the canvas lands "
                    "(within one half-float unit)",
                    dx, dy));
    if (auto skipped = camera_unjudged(c, "camera-region")) return *skipped;
    LoadOptions how;
    how.camera =
        ViewTransform{-double(dx), -double(dy), 1, c.spec.width + 2 * dx, c.spec.height + 2 * dy};
    auto seen = outputs_in(c, s, w, case_layout(c, params), name + ".camera", floors, how);
    if (!seen) return seen.error();
    if (!*seen) return relation.finish();  // the load failure is recorded already
    for (size_t i = 0; i < floors.size(); ++i) {
        // Why one unit: as for canvas-size, a sampling position normalised by the output's size
        // rounds differently for another size.
        const ImageRGBA& g = (**seen)[i];
        ImageRGBA cropped(c.spec.width, c.spec.height);
        for (uint32_t y = 0; y < c.spec.height; ++y)
            std::copy_n(g.at(dx, y + dy), 4 * c.spec.width, cropped.at(0, y));
        compare_within(floors[i], cropped, half_ulp, "through the camera", relation);
    }
    heat = relation.heat_maps();
    return relation.finish();
}

// Each pixel of `half` (the render at 1/2) against `whole` over the 2x2 scene pixels it covers
// and kCameraScaleReach around them: the range each channel takes there, widened by
// kCameraScaleUnits half-float units and by `tolerance` times its largest magnitude. Returns
// the least tolerance that would take every pixel (infinity if some pixel strays where the whole
// render is 0).
float compare_to_whole(const FloorImages& floor, const ImageRGBA& half, float tolerance,
                       CheckAccumulator& out) {
    float needed = 0;
    const ImageRGBA& whole = *floor.output;
    const uint32_t r = kCameraScaleReach;
    for (uint32_t j = 0; j < half.height; ++j)
        for (uint32_t i = 0; i < half.width; ++i) {
            const uint32_t x0 = 2 * i > r ? 2 * i - r : 0, y0 = 2 * j > r ? 2 * j - r : 0;
            const uint32_t x1 = std::min(whole.width, 2 * i + 2 + r);
            const uint32_t y1 = std::min(whole.height, 2 * j + 2 + r);
            const float* v = half.at(i, j);
            for (int k = 0; k < 4; ++k) {
                if (std::isnan(v[k])) continue;  // `finite` says so
                float lo = INFINITY, hi = -INFINITY;
                for (uint32_t y = y0; y < y1; ++y)
                    for (uint32_t x = x0; x < x1; ++x) {
                        const float w = whole.at(x, y)[k];
                        if (std::isnan(w)) continue;
                        lo = std::min(lo, w), hi = std::max(hi, w);
                    }
                if (!(lo <= hi)) continue;  // every pixel there NaN: `finite` says so
                const float largest = std::max(std::fabs(lo), std::fabs(hi));
                const float rounding = kCameraScaleUnits * half_ulp(largest);
                const float slack = rounding + tolerance * largest;
                if (v[k] >= lo - slack && v[k] <= hi + slack) continue;
                const float beyond = std::max(lo - v[k], v[k] - hi) - rounding;
                needed = std::max(needed, largest > 0 ? beyond / largest : INFINITY);
                out.violation(
                    floor, 2 * i, 2 * j,
                    fmt::format("{} at 1/2 (pixel {}, {}), where the whole render has {} from {:g} "
                                "to {:g} within {} scene pixel: {}",
                                format_rgba(v), i, j, "rgba"[k], lo, hi, r,
                                largest > 0
                                    ? fmt::format("a scale_tolerance of {:.3g} would "
                                                  "take it",
                                                  beyond / largest)
                                    : std::string("no scale_tolerance takes it (0 there)")));
                break;
            }
        }
    return needed;
}

Result<CheckResult> camera_scale(const CaseContext& c, Session& s, CaseWriter& w,
                                 const json& params, const std::string& name,
                                 const std::vector<FloorImages>& floors,
                                 std::map<int64_t, ImageRGBA>& heat) {
    const float tolerance = c.plugin.scale_tolerance;
    CheckAccumulator relation(
        "camera-scale",
        fmt::format("the same floors through a camera at scale 1/2 lie, pixel by pixel, within "
                    "the whole render's range over the scene pixels each covers and {} around, "
                    "widened by {:g} of its largest value (the declared scale_tolerance)",
                    kCameraScaleReach, tolerance));
    if (auto skipped = camera_unjudged(c, "camera-scale")) return *skipped;
    // The whole canvas at 1/2: each output pixel covers 2x2 scene pixels and its centre is
    // their shared corner, so the floors' tiles reach the effect averaged over those four.
    LoadOptions how;
    how.camera = ViewTransform{0, 0, 0.5, c.spec.width / 2, c.spec.height / 2};
    auto seen = outputs_in(c, s, w, case_layout(c, params), name + ".half", floors, how);
    if (!seen) return seen.error();
    if (!*seen) return relation.finish();  // the load failure is recorded already
    float needed = 0;
    for (size_t i = 0; i < floors.size(); ++i)
        needed = std::max(needed, compare_to_whole(floors[i], (**seen)[i], tolerance, relation));
    heat = relation.heat_maps();
    CheckResult result = relation.finish();
    if (needed > 0)
        result.message += std::isfinite(needed)
                              ? fmt::format(
                                    " (every pixel here would take a scale_tolerance of "
                                    "{:.3g})",
                                    needed)
                              : " (no scale_tolerance takes every pixel: some stray where the "
                                "whole render is 0)";
    return result;
}

// Whether a second load of the case's own scene gives the plugin's outputs bit for bit: a
// relation compares loads, so it means nothing for a plugin whose loads differ anyway (which
// `determinism` reports).
Result<std::optional<bool>> loads_agree(const CaseContext& c, Session& s, CaseWriter& w,
                                        const json& params, const std::string& name,
                                        const std::vector<FloorImages>& floors) {
    auto again = outputs_in(c, s, w, case_layout(c, params), name + ".again", floors, {});
    if (!again) return again.error();
    if (!*again) return std::optional<bool>();
    for (size_t i = 0; i < floors.size(); ++i)
        if (compare_exact(*floors[i].output, (**again)[i], floors[i].floor).pixels)
            return std::optional(false);
    return std::optional(true);
}

}  // namespace

Result<CheckResult> check_relation(const CaseContext& c, Session& s, CaseWriter& w,
                                   const json& params, const std::string& name,
                                   const std::vector<FloorImages>& floors,
                                   std::map<int64_t, ImageRGBA>& heat) {
    auto agree = loads_agree(c, s, w, params, name, floors);
    if (!agree) return agree.error();
    if (!*agree || !**agree) {
        CheckResult skipped;
        skipped.check = to_string(c.spec.relation);
        skipped.verdict = Verdict::Skip;
        skipped.message = *agree ? "not judged: a second load of the same scene rendered the "
                                   "plugin differently (see determinism)"
                                 : "not judged: the scene did not load again";
        return skipped;
    }
    switch (c.spec.relation) {
        case Relation::CanvasSize:
            return canvas_size(c, s, w, params, name, floors, heat);
        case Relation::FormatAgreement:
            return format_agreement(c, s, w, params, name, floors, heat);
        case Relation::CameraRegion:
            return camera_region(c, s, w, params, name, floors, heat);
        case Relation::CameraScale:
            return camera_scale(c, s, w, params, name, floors, heat);
        case Relation::None:
            break;
    }
    return make_error(ErrorCode::InvalidInput, "check_relation: the case names no relation");
}

}  // namespace acetate::harness
