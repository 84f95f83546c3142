#include "contract_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/sha256.hpp"

namespace acetate::harness {
namespace {

bool all_finite(const float* p) {
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) && std::isfinite(p[3]);
}

std::string fmt_float(float v) {
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
    return fmt::format("{:.9g}", v);
}

}  // namespace

std::string format_rgba(const float* p) {
    return fmt::format("({}, {}, {}, {})", fmt_float(p[0]), fmt_float(p[1]), fmt_float(p[2]),
                       fmt_float(p[3]));
}

CheckAccumulator::CheckAccumulator(std::string check, std::string passing_message)
    : passing_message_(std::move(passing_message)) {
    result_.check = std::move(check);
}

void CheckAccumulator::violation(const FloorImages& floor, uint32_t x, uint32_t y,
                                 std::string what) {
    ++result_.violations;
    if (result_.examples.size() < kMaxExamples) {
        Violation v;
        v.x = x;
        v.y = y;
        v.floor = floor.floor;
        if (floor.input) std::memcpy(v.input.data(), floor.input->at(x, y), sizeof(float) * 4);
        std::memcpy(v.output.data(), floor.output->at(x, y), sizeof(float) * 4);
        v.what = std::move(what);
        result_.examples.push_back(std::move(v));
    }
    auto [it, fresh] = heat_.try_emplace(floor.floor);
    ImageRGBA& heat = it->second;
    if (fresh) {
        heat = ImageRGBA(floor.output->width, floor.output->height);
        const ImageRGBA& context = floor.input ? *floor.input : *floor.output;
        for (uint32_t py = 0; py < heat.height; ++py)
            for (uint32_t px = 0; px < heat.width; ++px) {
                const float a = std::isfinite(context.at(px, py)[3])
                                    ? 0.25f * std::clamp(context.at(px, py)[3], 0.0f, 1.0f)
                                    : 0.0f;
                float* h = heat.at(px, py);
                h[0] = h[1] = h[2] = a;
                h[3] = 1.0f;
            }
    }
    float* h = heat.at(x, y);
    h[0] = 1.0f;
    h[1] = h[2] = 0.0f;
}

CheckResult CheckAccumulator::finish(Verdict failing) {
    if (result_.violations == 0) {
        result_.verdict = Verdict::Pass;
        result_.message = passing_message_;
        return result_;
    }
    result_.verdict = failing;
    const Violation& first = result_.examples.front();
    result_.message = fmt::format("{} pixel{} fail; first at ({}, {}){}: {}", result_.violations,
                                  result_.violations == 1 ? "" : "s", first.x, first.y,
                                  first.floor >= 0 ? fmt::format(" on floor {}", first.floor)
                                                   : std::string(" of the composite"),
                                  first.what);
    return result_;
}

float colour_at_zero_alpha_tolerance(const ImageRGBA& input) {
    float ratio = 1.0f;
    for (uint32_t y = 0; y < input.height; ++y)
        for (uint32_t x = 0; x < input.width; ++x) {
            const float* p = input.at(x, y);
            if (all_finite(p) && p[3] > 0.0f)
                ratio = std::max(ratio, std::max({p[0], p[1], p[2]}) / p[3]);
        }
    return kZeroAlpha * ratio;
}

void check_premultiplied(const FloorImages& floor, CheckAccumulator& out) {
    const ImageRGBA& image = *floor.output;
    const float tolerance = colour_at_zero_alpha_tolerance(*floor.input);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const float* p = image.at(x, y);
            if (!all_finite(p) || p[3] >= kZeroAlpha) continue;
            if (std::abs(p[0]) > tolerance || std::abs(p[1]) > tolerance ||
                std::abs(p[2]) > tolerance)
                out.violation(floor, x, y,
                              fmt::format("a = {} but rgb = ({}, {}, {}) (tolerance {})",
                                          fmt_float(p[3]), fmt_float(p[0]), fmt_float(p[1]),
                                          fmt_float(p[2]), fmt_float(tolerance)));
        }
}

void check_coverage(const FloorImages& floor, bool expanding, CheckAccumulator& out) {
    const ImageRGBA &in = *floor.input, &image = *floor.output;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const float a_in = in.at(x, y)[3], a_out = image.at(x, y)[3];
            if (!all_finite(image.at(x, y))) continue;
            if (!expanding && a_out != a_in)
                out.violation(floor, x, y,
                              fmt::format("alpha {} became {} (a coverage-preserving effect must "
                                          "keep alpha bit for bit)",
                                          fmt_float(a_in), fmt_float(a_out)));
            else if (expanding && (a_out < a_in || a_out > 1.0f))
                out.violation(floor, x, y,
                              fmt::format("alpha {} became {} (an expanding effect may only "
                                          "raise alpha, up to 1)",
                                          fmt_float(a_in), fmt_float(a_out)));
        }
}

void check_alpha_leak(const FloorImages& floor, CheckAccumulator& out) {
    const ImageRGBA &in = *floor.input, &image = *floor.output;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const float* p = image.at(x, y);
            if (in.at(x, y)[3] == 1.0f && all_finite(p) && p[3] < 1.0f)
                out.violation(floor, x, y,
                              fmt::format("opaque input became alpha {}: the floors below "
                                          "would show through",
                                          fmt_float(p[3])));
        }
}

void check_finite(const FloorImages& floor, CheckAccumulator& out) {
    const ImageRGBA& image = *floor.output;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x)
            if (!all_finite(image.at(x, y)))
                out.violation(floor, x, y,
                              fmt::format("non-finite value {}", format_rgba(image.at(x, y))));
}

void check_non_negative(const FloorImages& floor, CheckAccumulator& out) {
    const ImageRGBA& image = *floor.output;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const float* p = image.at(x, y);
            if (all_finite(p) && std::min({p[0], p[1], p[2], p[3]}) < 0.0f)
                out.violation(floor, x, y, fmt::format("negative value {}", format_rgba(p)));
        }
}

std::vector<CheckResult> check_contract(
    const std::vector<FloorImages>& floors, bool expanding,
    std::map<std::string, std::map<int64_t, ImageRGBA>>* heat_maps,
    const std::vector<FloorImages>& finite_only) {
    CheckAccumulator premultiplied("premultiplied",
                                   "rgb within 2^-24 of 0 (times the input's largest rgb/a, if "
                                   "above 1) wherever alpha is below 2^-24");
    CheckAccumulator coverage("coverage", expanding ? "alpha never dropped and stayed within 1 "
                                                      "(declared coverage-expanding)"
                                                    : "alpha kept bit for bit (declared "
                                                      "coverage-preserving)");
    CheckAccumulator leak("alpha-leak", "opaque input stayed opaque");
    CheckAccumulator finite("finite", "no NaN or infinity in any channel");
    CheckAccumulator non_negative("non-negative", "no channel below 0");
    for (const FloorImages& floor : floors) {
        check_non_negative(floor, non_negative);
        check_premultiplied(floor, premultiplied);
        check_coverage(floor, expanding, coverage);
        check_alpha_leak(floor, leak);
        check_finite(floor, finite);
    }
    for (const FloorImages& image : finite_only) check_finite(image, finite);
    std::vector<CheckResult> results;
    for (CheckAccumulator* acc : {&premultiplied, &coverage, &leak, &finite, &non_negative}) {
        CheckResult r = acc->finish();
        if (heat_maps && !acc->heat_maps().empty()) (*heat_maps)[r.check] = acc->heat_maps();
        results.push_back(std::move(r));
    }
    return results;
}

ImageDifference compare_exact(const ImageRGBA& a, const ImageRGBA& b, int64_t floor,
                              const ImageRGBA* only_where_transparent) {
    ImageDifference diff;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x) {
            if (only_where_transparent && only_where_transparent->at(x, y)[3] != 0.0f) continue;
            if (std::memcmp(a.at(x, y), b.at(x, y), sizeof(float) * 4) == 0) continue;
            ++diff.pixels;
            if (diff.examples.size() < kMaxExamples) {
                Violation v;
                v.x = x;
                v.y = y;
                v.floor = floor;
                std::memcpy(v.input.data(), a.at(x, y), sizeof(float) * 4);
                std::memcpy(v.output.data(), b.at(x, y), sizeof(float) * 4);
                v.what =
                    fmt::format("{} then {}", format_rgba(a.at(x, y)), format_rgba(b.at(x, y)));
                diff.examples.push_back(std::move(v));
            }
        }
    return diff;
}

void record_differences(const ImageRGBA& a, const ImageRGBA& b, int64_t floor,
                        const std::string& why, CheckAccumulator& out,
                        const ImageRGBA* only_where_transparent) {
    const FloorImages images{floor, &a, &b};
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x) {
            if (only_where_transparent && only_where_transparent->at(x, y)[3] != 0.0f) continue;
            if (std::memcmp(a.at(x, y), b.at(x, y), sizeof(float) * 4) == 0) continue;
            out.violation(images, x, y,
                          fmt::format("{}: {} then {}", why, format_rgba(a.at(x, y)),
                                      format_rgba(b.at(x, y))));
        }
}

std::string digest_images(const std::vector<const ImageRGBA*>& images) {
    std::string bytes;
    for (const ImageRGBA* image : images)
        bytes.append(reinterpret_cast<const char*>(image->pixels.data()),
                     image->pixels.size() * sizeof(float));
    return sha256_hex(bytes);
}

}  // namespace acetate::harness
