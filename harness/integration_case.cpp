// The integration stack: the plugin with the other integrated plugins, against a CPU reference.
#include <fmt/format.h>

#include <cstring>
#include <string>

#include "case_kinds.hpp"
#include "composite_reference.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Which floor's output the composite departs from the reference at first: floors 0..k
// composited for k = 0, 1, ..., each against the model of the same floors (k + 1 blends, so
// k + 1 roundings). Effects must be on for the floors and off for the composite.
Result<std::string> first_departure(Compositor& comp, const std::vector<ReferenceFloor>& floors,
                                    double time) {
    for (uint32_t k = 0; k < floors.size(); ++k) {
        ACETATE_TRY(comp.render(k, time));
        auto prefix = comp.read_accumulation();
        if (!prefix) return prefix.error();
        const double fail = k + 1;
        const ReferenceComparison cmp =
            compare_to_reference(composite_reference(floors, k + 1), *prefix, fail / 2, fail);
        if (cmp.worst <= fail) continue;
        const std::string below = k == 0   ? "the transparent canvas"
                                  : k == 1 ? "floor 0"
                                           : fmt::format("floors 0..{}", k - 1);
        return fmt::format(
            "first departs after floor {} (floor {}'s output over {}) at ({}, {}): {:.3g} "
            "roundings, fail above {}",
            k, k, below, cmp.x, cmp.y, cmp.worst, fail);
    }
    return std::string(
        "no prefix of the floors departs when composited floor by floor: the "
        "composite differed only in the full render");
}

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
        // Judged on its own input and output: the composite after the global effects before
        // it (an expanding one among them may have grown coverage already), and after it.
        const uint32_t index = uint32_t(layout.global_effects.size() - 1);
        auto capture = capture_global_effect(**comp, spec.floors - 1, spec.time, index);
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

    // Reference: the floors' outputs composited on the CPU as an RGBA16F target holds them
    // after each blend (composite_reference.hpp), gated as the host gates them.
    (**comp).set_effects_enabled(true, false);
    ACETATE_TRY((**comp).render(spec.floors - 1, spec.time));
    auto composite = (**comp).read_accumulation();
    if (!composite) return composite.error();  // the case stops: no later frame needs effects
    std::vector<ReferenceFloor> floors;
    for (uint32_t f = 0; f < spec.floors; ++f)
        floors.push_back({&captures[f].input, &captures[f].output, expanding[f]});
    const std::vector<PixelReference> model = composite_reference(floors, spec.floors);
    // In the manner of idiff's -fail / -warn / -failpercent 0: each blend rounds once, and
    // "over" only scales earlier errors by (1 - a) <= 1, so a correct composite is within
    // `floors` roundings of the running peak (fail above, at any pixel); warn above half that.
    // Saturation keeps the bound (clamping never widens an error), and the overflow model is
    // followed separately: composite_reference.cpp.
    const double fail_steps = spec.floors;
    const ReferenceComparison cmp =
        compare_to_reference(model, *composite, fail_steps / 2, fail_steps);
    const ImageRGBA reference = saturated_image(model, spec.width, spec.height);
    CheckResult ref;
    ref.check = "reference";
    ref.message = fmt::format(
        "composite against the CPU reference: worst {:.3g} roundings at ({}, {}); fail above {} "
        "(one per blend), warn above {}; {} pixels above warn, {} above fail",
        cmp.worst, cmp.x, cmp.y, fail_steps, fail_steps / 2, cmp.warn_pixels, cmp.fail_pixels);
    if (cmp.worst > fail_steps) {
        ref.verdict = Verdict::Fail;
        ref.violations = cmp.fail_pixels;
        Violation v;
        v.x = cmp.x;
        v.y = cmp.y;
        std::memcpy(v.input.data(), reference.at(cmp.x, cmp.y), 16);
        std::memcpy(v.output.data(), composite->at(cmp.x, cmp.y), 16);
        v.what = "reference (saturating model) then composite";
        ref.examples.push_back(v);
        auto first = first_departure(**comp, floors, spec.time);
        if (!first) return first.error();
        ref.message += "; " + *first;
    } else if (cmp.worst > fail_steps / 2) {
        ref.verdict = Verdict::Warn;
    }
    (**comp).set_effects_enabled(true, true);
    w.case_picture("composite", *composite);
    w.case_picture("reference", reference);
    w.add(ref);
    return {};
}

void plan_integration(const PlanContext& context, Planner& p) {
    CaseSpec s = p.contract("integration/stack",
                            "four floors with the other integrated plugins, against the "
                            "composite rebuilt from each floor rendered alone",
                            256, 160, Pattern::Standard, 4);
    s.kind = CaseKind::Integration;
    s.companions = context.companions;
    p.add(s);
    if (context.strictness >= 5) {
        s = p.contract("integration/stack-hdr",
                       "the same stack on HDR inputs near the half-float maximum", 128, 96,
                       Pattern::Hdr, 4);
        s.kind = CaseKind::Integration;
        s.companions = context.companions;
        p.add(s);
    }
}

}  // namespace acetate::harness
