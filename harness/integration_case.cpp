// The integration stack: the plugin with the other integrated plugins, against a CPU reference.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "case_kinds.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
constexpr double kHalfMax = 65504.0;
// One rgba16f rounding: within one ULP, 2^-10 of the value (Vulkan allows rounding toward zero
// as well as to nearest), or 2^-24 for subnormals (as in tests/composite_accuracy_test.cpp).
constexpr double kHalfRelative = 0x1p-10, kHalfAbsolute = 0x1p-24;
}  // namespace

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

}  // namespace acetate::harness
