#include "process_hygiene.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace acetate::harness {

ProcessHygieneWatcher::ProcessHygieneWatcher() {
    set_plugin_call_watcher(this);
}

ProcessHygieneWatcher::~ProcessHygieneWatcher() {
    if (watching_) set_plugin_call_watcher(nullptr);
}

void ProcessHygieneWatcher::before_call(std::string_view, const std::string&) {
    before_.push_back(capture_process_state());
}

void ProcessHygieneWatcher::after_call(std::string_view call, const std::string& plugin) {
    if (before_.empty()) return;
    const ProcessState before = std::move(before_.back());
    before_.pop_back();
    ++calls_;
    for (const std::string& change : process_differences(before, capture_process_state()))
        changes_.push_back(fmt::format("{} of {}: {}", call, plugin, change));
}

CheckResult ProcessHygieneWatcher::check() {
    if (watching_) set_plugin_call_watcher(nullptr);
    watching_ = false;
    CheckResult check;
    check.check = "process-hygiene";
    if (changes_.empty()) {
        check.message = fmt::format(
            "{} plugin calls (loads, builds, unloads) each left the floating-point environment, "
            "signals, environment, descriptors, threads, working folder, umask and locale as "
            "they found them",
            calls_);
        return check;
    }
    check.verdict = Verdict::Fail;
    check.violations = changes_.size();
    constexpr size_t kShown = 4;
    std::vector<std::string> shown(changes_.begin(),
                                   changes_.begin() + std::min(changes_.size(), kShown));
    check.message = fmt::format(
        "a plugin call changed the process it ran in: {}{}", fmt::join(shown, "; "),
        changes_.size() > kShown ? fmt::format("; and {} more", changes_.size() - kShown)
                                 : std::string());
    return check;
}

}  // namespace acetate::harness
