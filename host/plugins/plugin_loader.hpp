#pragma once
// Finds and loads effect plugins with Boost.DLL. Only plugins a scene names are loaded; each
// file is loaded once per process and shared by every scene that names it.

#include <acetate/effect.h>

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
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
    // SHA-256 of the bytes loaded: the sealed copy that was judged and mapped, which may differ
    // from what `file` holds by the time anyone hashes it again.
    std::string binary_sha256;
    std::shared_ptr<boost::dll::shared_library> library;
    const AcetateEffectApi* api = nullptr;
    EffectDescriptor descriptor;
};

// What PluginLoader::reload_changed() found for one plugin loaded by id.
struct PluginReloadOutcome {
    std::string id;
    std::filesystem::path file;  // the file it was loaded from
    bool changed = false;        // the file's bytes differ from those loaded (or it is gone)
    // The plugin now served for `id`: the new one when the changed file was admitted and
    // opened, else the old one.
    std::shared_ptr<LoadedPlugin> plugin;
    std::optional<Error> refused;  // why the changed file was not taken
};

class PluginLoader {
  public:
    // Decides whether a plugin file may be loaded into this process: called once the file is
    // found and before it is loaded (dlopen runs the library's static constructors, so a
    // refused file must never reach it). `id` is the id asked for by load(), or empty for
    // load_file(), whose id is not known before loading (a policy then judges the file by its
    // bytes alone). `contents` names a sealed memory copy of the file (/proc/self/fd/N,
    // sealed_library.hpp): that copy is what gets loaded if admitted, so a policy that reads
    // its bytes from `contents` judges exactly what runs, even if `file` is rewritten in place
    // or replaced meanwhile. An error refuses the file and is returned by load() / load_file()
    // as is.
    using Admission =
        std::function<Result<void>(const std::string& id, const std::filesystem::path& file,
                                   const std::filesystem::path& contents)>;

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

    // Checks every plugin loaded by id against the file it came from: a file whose bytes
    // (SHA-256) differ from those loaded goes through the admission hook again and is opened;
    // it then serves later load() calls for that id, while the old library stays loaded as
    // long as something holds it. A changed file that is refused, gone, broken or declares
    // another id leaves the old plugin serving, and the outcome says why. One outcome per
    // plugin, in id order.
    std::vector<PluginReloadOutcome> reload_changed();

    // Loads one file, whatever its id (the admission hook gets an empty id).
    Result<std::shared_ptr<LoadedPlugin>> load_file(const std::filesystem::path& file);

    // Sets the hook every later load() and load_file() asks before opening a file. Without
    // one (the default, for tests and tools) every file found is loaded; `acetate render`
    // and the embedding API set the registry's load policy (registry/load_policy.hpp). An empty
    // function removes the hook. load() asks once per id: a loaded plugin is kept and not asked
    // again.
    void set_admission(Admission admission) { admission_ = std::move(admission); }

    const std::vector<std::filesystem::path>& directories() const { return directories_; }
    // Plugins loaded so far by this loader, by id.
    size_t loaded_count() const { return by_id_.size(); }

  private:
    // Asks the admission hook (if any) about `file`, then opens it.
    Result<std::shared_ptr<LoadedPlugin>> admit_and_open(const std::string& id,
                                                         const std::filesystem::path& file);
    // Opens `library` and reads its descriptor; no admission check. Messages and
    // LoadedPlugin::file name `file` (what the user knows it as).
    Result<std::shared_ptr<LoadedPlugin>> open_library(const std::filesystem::path& library,
                                                       const std::filesystem::path& file);

    std::vector<std::filesystem::path> directories_;
    std::map<std::string, std::shared_ptr<LoadedPlugin>> by_id_;
    Admission admission_;
};

}  // namespace acetate
