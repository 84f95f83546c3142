// The Golden case: the fixed reference scene rendered, its output written for `bless`, and
// compared with the blessed image under the plugin's gates (references.hpp).
#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "case_kinds.hpp"
#include "image_compare.hpp"
#include "references.hpp"
#include "scene/scene.hpp"

namespace acetate::harness {
namespace {

using nlohmann::json;

// The share (0..1) of the pixels whose largest channel difference is over `threshold`, each
// pixel weighted by the larger of its two alphas: where neither image covers anything, a
// difference weighs nothing (it is also 0 there for a plugin that keeps the contract).
double alpha_weighted_share(const ImageRGBA& test, const ImageRGBA& reference, double threshold) {
    double over = 0, total = 0;
    for (size_t i = 0; i < test.pixels.size(); i += 4) {
        double largest = 0;
        for (size_t k = 0; k < 4; ++k) {
            const double d = std::fabs(double(test.pixels[i + k]) - reference.pixels[i + k]);
            largest = std::isfinite(d) ? std::max(largest, d) : INFINITY;
        }
        const double weight =
            std::max({double(test.pixels[i + 3]), double(reference.pixels[i + 3]), 0.0});
        total += weight;
        if (largest > threshold) over += std::isfinite(weight) ? weight : 1.0;
    }
    return total > 0 ? over / total : 0.0;
}

ReferenceGates gates_of(const json& j) {
    ReferenceGates g;
    g.warn = j.at("warn").get<double>();
    g.fail = j.at("fail").get<double>();
    g.fail_percent = j.at("fail_percent").get<double>();
    g.hard_fail = j.at("hard_fail").get<double>();
    return g;
}

// What the case compares: on the shared scene, what the plugin produced (its floor's target, or
// the composite it ran on); on one of the plugin's own scenes, the picture as a user sees it
// (the composite over the canvas, the scene's active floor on top). Null when the load failed
// (recorded).
Result<std::optional<ImageRGBA>> render_reference(const CaseContext& c, Session& s, CaseWriter& w) {
    if (c.spec.scene_file.empty()) {
        auto comp = load_layout(c, s, w, case_layout(c), "golden");
        if (!comp) return comp.error();
        if (!*comp) return std::optional<ImageRGBA>();
        const uint32_t floor = c.plugin.is_global() ? c.spec.floors - 1 : plugin_floors(c).front();
        auto output = plugin_output(**comp, c.plugin.is_global(), floor, c.spec.time);
        if (!output) return output.error();
        return std::optional<ImageRGBA>(std::move(output.value()));
    }
    auto scene = parse_scene_file(c.spec.scene_file);
    if (!scene) return scene.error();
    auto comp = load_scene(c, s, w, scene.value());
    if (!comp) return comp.error();
    if (!*comp) return std::optional<ImageRGBA>();
    (*comp)->set_view(OutputView::Normal);
    ACETATE_TRY((*comp)->render(scene->active_floor, c.spec.time));
    auto output = (*comp)->read_output();
    if (!output) return output.error();
    return std::optional<ImageRGBA>(std::move(output.value()));
}

}  // namespace

Result<void> run_golden(const CaseContext& c, Session& s, CaseWriter& w) {
    auto rendered = render_reference(c, s, w);
    if (!rendered) return rendered.error();
    if (!rendered.value()) return {};  // the load failure is recorded
    const std::optional<ImageRGBA>& output = rendered.value();
    ACETATE_TRY(save_image(golden_output_file(c.case_directory), *output));
    w.case_picture("output.golden", *output);

    CheckResult check;
    check.check = "golden";
    if (c.spec.reference.is_null()) {
        check.verdict = Verdict::Skip;
        check.message = fmt::format(
            "no image blessed for this source: rendered only (acetate-harness bless {} "
            "--by NAME blesses this output)",
            c.plugin.file);
        w.add(std::move(check));
        return {};
    }
    const std::string file = c.spec.reference.at("image").get<std::string>();
    const ReferenceGates gates = gates_of(c.spec.reference.at("gates"));
    // A reference that cannot be used fails the check, naming the file: the plugin is not at
    // fault, but nothing vouches for its colour either.
    auto unusable = [&](const std::string& why) {
        check.verdict = Verdict::Fail;
        check.message = fmt::format("{}: {}; bless again (acetate-harness bless {} --by NAME)",
                                    file, why, c.plugin.file);
        w.add(std::move(check));
        return Result<void>{};
    };
    auto reference = load_image(file, ImageRole::Colour);
    if (!reference) return unusable(reference.error().message);
    if (reference->width != output->width || reference->height != output->height)
        return unusable(fmt::format("the reference is {}x{}, the case renders {}x{}",
                                    reference->width, reference->height, output->width,
                                    output->height));
    w.case_picture("reference.golden", *reference);
    ImageRGBA heat;
    auto stats = compare_images(*output, *reference, {gates.warn, gates.fail}, &heat);
    if (!stats) return unusable(stats.error().message);
    const double share = alpha_weighted_share(*output, *reference, gates.fail);
    const uint64_t pixels = uint64_t(output->width) * output->height;
    check.violations = uint64_t(std::llround(stats->fail_share * double(pixels)));
    check.message = fmt::format(
        "against {}: max {:.3g} half-float roundings (|d| {:.3g}), mean |d| {:.3g}, PSNR {:.1f} "
        "dB; {:.3f}% of alpha-weighted pixels over {:.4g} (gate {}%), hard limit {}",
        file, stats->max_roundings, stats->max_abs, stats->mean_abs, stats->psnr_db, share * 100.0,
        gates.fail, gates.fail_percent, gates.hard_fail);
    if (!stats->finite || stats->max_abs > gates.hard_fail || share * 100.0 > gates.fail_percent)
        check.verdict = Verdict::Fail;
    else if (stats->max_abs > gates.warn)
        check.verdict = Verdict::Warn;
    const std::map<int64_t, ImageRGBA> heat_maps = {{-1, std::move(heat)}};
    w.add(std::move(check), &heat_maps);
    return {};
}

void plan_golden(const PlanContext& context, Planner& p) {
    // The reference cases are the same at every strictness and seed (references.hpp).
    for (CaseSpec& golden : golden_cases(context.plugin)) p.add_as_is(std::move(golden));
}

}  // namespace acetate::harness
