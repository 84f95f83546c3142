#pragma once
// Every call into a plugin's own code goes through one guard: loading its library (its static
// constructors) with the entry point, build() with last_error(), and unloading the library
// (its static destructors). A watcher set for the process (the validation harness's
// process-hygiene check) is told before and after each, so it can compare the process around
// exactly the plugin's code. With no watcher the guard costs a null check.

#include <string>
#include <string_view>

namespace acetate {

class PluginCallWatcher {
  public:
    virtual ~PluginCallWatcher() = default;
    // `call` is "load", "build" or "unload"; `plugin` the file or label the host knows it by.
    virtual void before_call(std::string_view call, const std::string& plugin) = 0;
    virtual void after_call(std::string_view call, const std::string& plugin) = 0;
};

// The process's watcher (null: none). The caller keeps it alive until it sets null again.
// Not thread-safe: set it before plugins are loaded, on the thread that loads them.
void set_plugin_call_watcher(PluginCallWatcher* watcher);

// Tells the watcher, if any, about one call for the guard's lifetime.
class PluginCallGuard {
  public:
    PluginCallGuard(std::string_view call, std::string plugin);
    ~PluginCallGuard();
    PluginCallGuard(const PluginCallGuard&) = delete;
    PluginCallGuard& operator=(const PluginCallGuard&) = delete;

  private:
    PluginCallWatcher* watcher_;
    std::string_view call_;
    std::string plugin_;
};

}  // namespace acetate
