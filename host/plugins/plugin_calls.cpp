#include "plugins/plugin_calls.hpp"

namespace acetate {
namespace {

PluginCallWatcher* g_watcher = nullptr;

}  // namespace

void set_plugin_call_watcher(PluginCallWatcher* watcher) {
    g_watcher = watcher;
}

PluginCallGuard::PluginCallGuard(std::string_view call, std::string plugin)
    : watcher_(g_watcher), call_(call), plugin_(std::move(plugin)) {
    if (watcher_) watcher_->before_call(call_, plugin_);
}

PluginCallGuard::~PluginCallGuard() {
    if (watcher_) watcher_->after_call(call_, plugin_);
}

}  // namespace acetate
