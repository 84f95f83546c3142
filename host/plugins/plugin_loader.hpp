#pragma once
// Finds and loads effect plugins with Boost.DLL. Only plugins a scene names are loaded; each
// file is loaded once per process and shared by every scene that names it.

#include <acetate/effect.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "plugins/effect_descriptor.hpp"

namespace boost::dll {
class shared_library;
}

namespace acetate {

// A loaded plugin: the library stays loaded as long as this lives.
struct LoadedPlugin {
    std::filesystem::path file;
    std::shared_ptr<boost::dll::shared_library> library;
    const AcetateEffectApi* api = nullptr;
    EffectDescriptor descriptor;
};

class PluginLoader {
public:
    // Searches `directories` in order.
    explicit PluginLoader(std::vector<std::filesystem::path> directories);

    // The default search path: `extra` (--plugin-path), then ACETATE_PLUGIN_PATH (':'-separated),
    // then the installation's lib/acetate/plugins, then the build tree's plugins/ folder (both
    // found relative to the running executable).
    static std::vector<std::filesystem::path> default_directories(
        const std::vector<std::filesystem::path>& extra);

    // Loads the plugin with this id: looks for `<id>.so`, then `<last id segment>.so`, in each
    // directory. Errors name the file and what is wrong (no entry point, wrong ABI, malformed
    // descriptor, an id other than the one asked for), or list where it looked.
    Result<std::shared_ptr<LoadedPlugin>> load(const std::string& id);

    // Loads one file, whatever its id.
    Result<std::shared_ptr<LoadedPlugin>> load_file(const std::filesystem::path& file);

    const std::vector<std::filesystem::path>& directories() const { return directories_; }
    // Plugins loaded so far by this loader, by id.
    size_t loaded_count() const { return by_id_.size(); }

private:
    std::vector<std::filesystem::path> directories_;
    std::map<std::string, std::shared_ptr<LoadedPlugin>> by_id_;
};

}  // namespace acetate
