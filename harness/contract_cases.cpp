// The contract cases (each output against its input) and the disconnected-parameter case.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "case_kinds.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;
using nlohmann::json;

// Renders the plugin's floors (or the composite) and checks each against its input.
Result<void> run_contract(const CaseContext& c, Session& s, CaseWriter& w) {
    auto comp = load_layout(c, s, w, plugin_everywhere(c), "scene");
    if (!comp) return comp.error();
    if (!*comp) return {};
    std::vector<Capture> captures;
    std::vector<FloorImages> floors;
    if (c.plugin.is_global()) {
        auto capture = capture_global(**comp, c.spec.floors - 1, c.spec.time);
        if (!capture) return capture.error();
        captures.push_back(std::move(capture.value()));
    } else {
        for (uint32_t f = 0; f < c.spec.floors; ++f) {
            auto capture = capture_floor(**comp, f, c.spec.time);
            if (!capture) return capture.error();
            captures.push_back(std::move(capture.value()));
        }
    }
    for (size_t i = 0; i < captures.size(); ++i) {
        const int64_t floor = c.plugin.is_global() ? -1 : int64_t(i);
        floors.push_back({floor, &captures[i].input, &captures[i].output});
        const std::string suffix = floor >= 0 ? fmt::format("floor{}", floor) : "composite";
        w.case_picture("input." + suffix, captures[i].input);
        w.case_picture("output." + suffix, captures[i].output);
    }
    // NaN/Inf anywhere: the composite of every floor with all effects on, too.
    ACETATE_TRY((**comp).render(c.spec.floors - 1, c.spec.time));
    auto composite = (**comp).read_accumulation();
    if (!composite) return composite.error();
    w.case_picture("composite", *composite);
    std::map<std::string, std::map<int64_t, ImageRGBA>> heat;
    w.add_all(
        check_contract(floors, c.plugin.is_expanding(), &heat, {{-1, nullptr, &composite.value()}}),
        heat);
    return {};
}

// Two frames of each floor must match bit for bit; the digest lets the parent compare two
// processes. The outputs are kept as EXR so the parent can show where they differ.
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
                auto comp = load_layout(c, s, w, plugin_everywhere(c, params), name);
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

}  // namespace acetate::harness
