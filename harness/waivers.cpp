#include "waivers.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "checks.hpp"

namespace acetate::harness {

const std::vector<std::string>& waivable_checks() {
    static const std::vector<std::string> checks = [] {
        std::vector<std::string> out;
        for (const CheckInfo& c : registered_checks())
            if (c.waivable) out.emplace_back(c.name);
        out.emplace_back(kStrictnessWaiver);
        return out;
    }();
    return checks;
}

std::string utc_today() {
    return utc_now_iso8601().substr(0, 10);  // YYYY-MM-DD of YYYY-MM-DDTHH:MM:SSZ
}

void apply_waivers(std::vector<CaseResult>& results, const std::vector<Waiver>& waivers,
                   std::string_view today) {
    for (CaseResult& c : results) {
        bool changed = false;
        for (CheckResult& check : c.checks) {
            if (check.verdict != Verdict::Fail) continue;
            for (const Waiver& w : waivers)
                if (w.check == check.check && !w.expired(today)) {
                    check.verdict = Verdict::Waived;
                    check.message = fmt::format("waived until {} by {} ({}): {}", w.until, w.by,
                                                w.reason, check.message);
                    changed = true;
                }
        }
        // A case's verdict is the worst of its checks', unless its process failed.
        if (changed && c.verdict == Verdict::Fail) {
            c.verdict = Verdict::Pass;
            for (const CheckResult& check : c.checks)
                c.verdict = std::max(c.verdict, check.verdict);
        }
    }
    std::vector<std::string> expired;
    for (const Waiver& w : waivers)
        if (w.expired(today)) expired.push_back(fmt::format("{} (until {})", w.check, w.until));
    if (expired.empty()) return;
    CaseResult c;
    c.id = "waivers/expired";
    c.description = "every waiver in the registry for this source still holds";
    c.verdict = Verdict::Fail;
    CheckResult check;
    check.check = "waiver";
    check.verdict = Verdict::Fail;
    check.message = fmt::format("expired: {}; renew (acetate-harness waive) or fix the plugin",
                                fmt::join(expired, ", "));
    c.message = check.message;
    c.checks.push_back(std::move(check));
    results.push_back(std::move(c));
}

std::vector<Waiver> waivers_of(const std::filesystem::path& registry, std::string_view id,
                               std::string_view version, std::string_view source_digest) {
    auto loaded = Registry::load(registry);
    if (!loaded) return {};
    const RegistryEntry* e = loaded->find(id, version);
    if (!e || e->source_digest != source_digest) return {};
    return e->waivers;
}

std::vector<std::string> waiver_lines(const std::vector<Waiver>& waivers, std::string_view today) {
    std::vector<std::string> lines;
    for (const Waiver& w : waivers)
        lines.push_back(fmt::format("{} until {}{} by {} at {} ({})", w.check, w.until,
                                    w.expired(today) ? " EXPIRED" : "", w.by, w.at, w.reason));
    return lines;
}

}  // namespace acetate::harness
