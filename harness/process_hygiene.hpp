#pragma once
// The `process-hygiene` check: a watcher of every plugin call in a case's child
// (plugins/plugin_calls.hpp) that compares the process before and after each call
// (process_state.hpp) and names what a call changed, which call, and which plugin.

#include <string>
#include <string_view>
#include <vector>

#include "plugins/plugin_calls.hpp"
#include "process_state.hpp"
#include "report.hpp"

namespace acetate::harness {

class ProcessHygieneWatcher final : public PluginCallWatcher {
  public:
    // Watches from now until destroyed (or until the check is taken).
    ProcessHygieneWatcher();
    ~ProcessHygieneWatcher() override;
    ProcessHygieneWatcher(const ProcessHygieneWatcher&) = delete;
    ProcessHygieneWatcher& operator=(const ProcessHygieneWatcher&) = delete;

    void before_call(std::string_view call, const std::string& plugin) override;
    void after_call(std::string_view call, const std::string& plugin) override;

    // Stops watching; PASS with the number of calls watched, or FAIL with every change, each
    // named with its call and plugin ("build of floor 0 (test.x): rounding mode: ...").
    CheckResult check();

  private:
    std::vector<ProcessState> before_;  // a stack: a call may run inside another (unload)
    std::vector<std::string> changes_;
    size_t calls_ = 0;
    bool watching_ = true;
};

}  // namespace acetate::harness
