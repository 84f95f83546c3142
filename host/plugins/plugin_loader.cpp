#include "plugins/plugin_loader.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "core/sha256.hpp"
#include "plugins/plugin_calls.hpp"
#include "plugins/sealed_library.hpp"

namespace acetate {
namespace {

// What dlopen said, without Boost.DLL's wrapping and without the library's own path (the
// caller names the file as the user gave it).
std::string dlopen_reason(const std::string& what, const std::string& library) {
    const std::string marker = "dlerror system message: ";
    std::string reason = what;
    if (const size_t at = what.find(marker); at != std::string::npos) {
        reason = what.substr(at + marker.size());
        if (const size_t end = reason.rfind("): "); end != std::string::npos)
            reason.resize(end);
        else if (!reason.empty() && reason.back() == ')')
            reason.pop_back();
    }
    if (reason.rfind(library + ": ", 0) == 0) reason.erase(0, library.size() + 2);
    return reason;
}

}  // namespace

PluginLoader::PluginLoader(std::vector<std::filesystem::path> directories)
    : directories_(std::move(directories)) {}

std::vector<std::filesystem::path> PluginLoader::default_directories(
    const std::vector<std::filesystem::path>& extra) {
    std::vector<std::filesystem::path> out = extra;
    if (const char* env = std::getenv("ACETATE_PLUGIN_PATH")) {
        std::stringstream list(env);
        std::string item;
        while (std::getline(list, item, ':'))
            if (!item.empty()) out.emplace_back(item);
    }
    boost::system::error_code ec;
    const std::filesystem::path exe = boost::dll::program_location(ec).string();
    if (!ec) {
        const auto bin = exe.parent_path();
        out.push_back(bin.parent_path() / ACETATE_INSTALL_LIBDIR / "acetate" /
                      "plugins");                      // installed
        out.push_back(bin.parent_path() / "plugins");  // build tree: build/host/acetate
    }
    // A program embedding the installed host library (PREFIX/<libdir>/libacetate-host.so)
    // from anywhere: the plugins installed beside that library.
    const std::filesystem::path library = boost::dll::this_line_location(ec).string();
    if (!ec) {
        const auto installed = library.parent_path() / "acetate" / "plugins";
        if (std::find(out.begin(), out.end(), installed) == out.end()) out.push_back(installed);
    }
    return out;
}

Result<std::shared_ptr<LoadedPlugin>> PluginLoader::load_file(const std::filesystem::path& file) {
    return admit_and_open(std::string(), file);
}

Result<std::shared_ptr<LoadedPlugin>> PluginLoader::admit_and_open(
    const std::string& id, const std::filesystem::path& file) {
    // The policy hashes, and dlopen maps, one sealed copy (sealed_library.hpp): nothing done to
    // the file on disk after this line can change what runs.
    auto sealed = seal_library(file, file.string());
    if (!sealed) return sealed.error();
    auto admitted = admission_ ? admission_(id, file, sealed->path) : Result<void>();
    if (!admitted) {
        ::close(sealed->fd);  // never mapped
        Error refused = admitted.error();
        refused.code = ErrorCode::PluginRefused;  // what a program may choose to leave out
        return refused;
    }
    // From here the memory file stays open for the life of the process, whatever happens: the
    // dynamic linker knows a library by the name "/proc/self/fd/N" (and may keep a refused one
    // mapped), so it would hand that library back for a later dlopen of the same name if the
    // number were reused for another plugin.
    auto plugin = open_library(sealed->path, file);
    if (!plugin) return plugin;
    plugin.value()->binary_sha256 = sealed->sha256;
    return plugin;
}

Result<std::shared_ptr<LoadedPlugin>> PluginLoader::open_library(
    const std::filesystem::path& library, const std::filesystem::path& file) {
    const std::string where = file.string();
    auto plugin = std::make_shared<LoadedPlugin>();
    plugin->file = file;
    // Loading runs the library's static constructors, and the entry point is its code too;
    // unloading (when the last holder lets go) runs its static destructors.
    PluginCallGuard loading("load", where);
    try {
        plugin->library = std::shared_ptr<boost::dll::shared_library>(
            new boost::dll::shared_library(library.string(), boost::dll::load_mode::rtld_now |
                                                                 boost::dll::load_mode::rtld_local),
            [where](boost::dll::shared_library* unloaded) {
                PluginCallGuard unloading("unload", where);
                delete unloaded;
            });
    } catch (const std::exception& e) {
        // Boost.DLL's exceptions carry dlerror()'s text: missing file, missing symbol, ...
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: cannot load the plugin: {}", where,
                                      dlopen_reason(e.what(), library.string())));
    }
    if (!plugin->library->has(ACETATE_ENTRY_POINT_NAME))
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: no entry point {}: not an Acetate effect plugin", where,
                                      ACETATE_ENTRY_POINT_NAME));
    auto entry = plugin->library->get<AcetateStatus(uint32_t, const AcetateEffectApi**)>(
        ACETATE_ENTRY_POINT_NAME);
    const AcetateEffectApi* api = nullptr;
    const AcetateStatus status = entry(ACETATE_ABI_VERSION, &api);
    if (status == ACETATE_ERROR_UNSUPPORTED_ABI)
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{}: the plugin cannot serve ABI version {}", where, ACETATE_ABI_VERSION));
    if (status != ACETATE_OK)
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{}: {} failed with status {}", where, ACETATE_ENTRY_POINT_NAME, status));
    if (!api)
        return make_error(ErrorCode::InvalidInput, fmt::format("{}: {} returned no function table",
                                                               where, ACETATE_ENTRY_POINT_NAME));
    if (api->struct_size < sizeof(AcetateEffectApi) || !api->build || !api->last_error)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: the function table is incomplete (struct_size {}, "
                                      "build and last_error must be set)",
                                      where, api->struct_size));
    auto descriptor = copy_descriptor(api->descriptor, where);
    if (!descriptor) return descriptor.error();
    plugin->api = api;
    plugin->descriptor = std::move(descriptor.value());
    return plugin;
}

std::vector<PluginReloadOutcome> PluginLoader::reload_changed() {
    std::vector<PluginReloadOutcome> outcomes;
    for (auto& [id, plugin] : by_id_) {
        PluginReloadOutcome outcome{id, plugin->file, false, plugin, std::nullopt};
        auto sha = file_sha256(plugin->file);
        if (sha && sha.value() == plugin->binary_sha256) {
            outcomes.push_back(std::move(outcome));
            continue;
        }
        outcome.changed = true;
        auto reopened = sha ? admit_and_open(id, plugin->file)
                            : Result<std::shared_ptr<LoadedPlugin>>(sha.error());
        if (reopened && reopened.value()->descriptor.id != id)
            reopened =
                make_error(ErrorCode::InvalidInput,
                           fmt::format("{}: declares id \"{}\", not \"{}\"", plugin->file.string(),
                                       reopened.value()->descriptor.id, id));
        if (reopened) {
            plugin = reopened.value();
            outcome.plugin = plugin;
        } else {
            outcome.refused = reopened.error();
        }
        outcomes.push_back(std::move(outcome));
    }
    return outcomes;
}

Result<std::shared_ptr<LoadedPlugin>> PluginLoader::load(const std::string& id) {
    if (auto found = by_id_.find(id); found != by_id_.end()) return found->second;
    // The id becomes a file name: only reverse-DNS ids, so no path can lead outside the
    // plugin directories.
    if (!is_reverse_dns(id))
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("plugin id \"{}\" is not a reverse-DNS name like "
                                      "\"com.example.glow\"",
                                      id));
    std::vector<std::string> names{id + ".so"};
    const std::string last = id.substr(id.rfind('.') + 1);
    if (last != id) names.push_back(last + ".so");
    std::string looked;
    for (const auto& dir : directories_) {
        for (const std::string& name : names) {
            const auto file = dir / name;
            looked += (looked.empty() ? "" : ", ") + file.string();
            std::error_code ec;
            if (!std::filesystem::is_regular_file(file, ec)) continue;
            // The first file found is the plugin: a refused one is not skipped for a later one.
            auto plugin = admit_and_open(id, file);
            if (!plugin) return plugin.error();
            if (plugin.value()->descriptor.id != id)
                return make_error(ErrorCode::InvalidInput,
                                  fmt::format("{}: declares id \"{}\", not \"{}\"", file.string(),
                                              plugin.value()->descriptor.id, id));
            by_id_[id] = plugin.value();
            return plugin;
        }
    }
    return make_error(ErrorCode::FileNotFound,
                      fmt::format("plugin \"{}\" not found; looked for {}", id,
                                  looked.empty() ? "nothing (empty search path)" : looked));
}

}  // namespace acetate
