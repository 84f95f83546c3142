// What a plugin declares (its id, version, parameters, presets, digests), read in this process
// or, for a plugin not yet trusted, in a `describe` child so that a crashing entry point is a
// clean error in the parent.

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/child_process.hpp"
#include "core/input_file.hpp"
#include "core/sha256.hpp"
#include "core/strict_json.hpp"
#include "plugins/plugin_loader.hpp"
#include "validate.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;

// The describe child's own error: what follows kDescribeErrorMarker on the last log line that
// starts with it; "" when no line does.
std::string own_describe_error(const std::string& log) {
    const std::string marker = kDescribeErrorMarker;
    std::istringstream in(log);
    std::string error;
    for (std::string line; std::getline(in, line);)
        if (line.rfind(marker, 0) == 0) error = line.substr(marker.size());
    return error;
}

// Why the describe child gave no plugin.json, in one line. The child runs plugin code (the
// entry point, info()), which can end the process any way it likes: exit() with any status,
// 0 and the harness's own included, _exit, abort, a signal. The one ending the harness controls
// is its own error path, so that one is made unmistakable (kDescribeFailure and a line starting
// with kDescribeErrorMarker: a plugin would have to forge both), and every other ending, a
// status 0 without plugin.json included, is the plugin's doing and said so; never "no
// plugin.json", which names the symptom and sends the author looking in the wrong place.
std::string describe_failure(const ChildOutcome& outcome, const std::string& log) {
    if (outcome.timed_out)
        return fmt::format("the plugin hung while describing itself ({})", outcome.message);
    if (!outcome.signal && outcome.exit_code == kDescribeFailure) {
        const std::string own = own_describe_error(log);
        if (!own.empty()) return own;
    }
    return with_log(plugin_ended(outcome, "while describing itself"), log);
}

}  // namespace

Result<PluginInfo> describe_plugin(const fs::path& file, const std::string& required_sha256) {
    PluginLoader loader({});
    if (!required_sha256.empty())
        loader.set_admission(
            [&](const std::string&, const fs::path&, const fs::path& contents) -> Result<void> {
                auto sha = file_sha256(contents);  // the sealed copy that would be loaded
                if (!sha) return sha.error();
                if (sha.value() == required_sha256) return {};
                return make_error(
                    ErrorCode::InvalidInput,
                    fmt::format("{}: not loaded: its SHA-256 {} is not the {} "
                                "required",
                                file.string(), sha->substr(0, 12), required_sha256.substr(0, 12)));
            });
    auto loaded = loader.load_file(file);
    if (!loaded) return loaded.error();
    const EffectDescriptor& d = loaded.value()->descriptor;
    PluginInfo info;
    info.file = fs::absolute(file).string();
    info.id = d.id;
    info.version = d.version_string();
    info.display_name = d.display_name;
    info.scope = d.scope == ACETATE_SCOPE_GLOBAL ? "global" : "floor";
    info.coverage = d.coverage == ACETATE_COVERAGE_EXPANDING ? "expanding" : "preserving";
    info.masks = d.masks;
    for (const EffectParam& p : d.params) {
        if (p.hidden) {
            info.hidden_params.push_back(p.name);
            continue;
        }
        const char* type = p.type == ACETATE_PARAM_INT     ? "int"
                           : p.type == ACETATE_PARAM_BOOL  ? "bool"
                           : p.type == ACETATE_PARAM_VEC2  ? "vec2"
                           : p.type == ACETATE_PARAM_VEC3  ? "vec3"
                           : p.type == ACETATE_PARAM_COLOR ? "color"
                                                           : "float";
        info.params.push_back(
            {p.name, type, p.default_value, p.min_value, p.max_value, p.components()});
    }
    info.abi = abi_version_string(d.abi_minor);
    info.scale_tolerance = d.scale_tolerance;
    for (const auto& [name, values] : d.presets) info.presets.push_back(name);
    info.source_digest = d.source_digest;
    info.binary_sha256 = loaded.value()->binary_sha256;  // what ran, not the file now
    return info;
}

Result<PluginInfo> describe_in_child(const fs::path& self, const fs::path& plugin,
                                     const fs::path& work_directory, double timeout_seconds) {
    std::error_code ec;
    fs::create_directories(work_directory, ec);
    if (ec)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot create: {}",
                                                     work_directory.string(), ec.message()));
    // The folder must take a file before the child runs: a full disk or a read-only folder is
    // the machine's fault, and said so here, rather than read later as the plugin ending the
    // describe child without its description.
    const fs::path probe = work_directory / ".write-probe";
    if (auto writable = write_file_atomically(probe, std::string(4096, '\n')); !writable)
        return writable.error();
    fs::remove(probe, ec);
    // The child writes into a folder of its own, made here, so that nothing another process
    // reads is ever removed or half written (shards sharing one folder, docs/cluster.md).
    std::string own = (work_directory / ".describe-XXXXXX").string();
    if (!mkdtemp(own.data()))
        return make_error(ErrorCode::Io,
                          fmt::format("{}: cannot create a folder: {}", own, std::strerror(errno)));
    struct RemovedAtEnd {
        fs::path folder;
        ~RemovedAtEnd() {
            std::error_code ignored;
            fs::remove_all(folder, ignored);
        }
    } removed{own};
    const fs::path out = fs::path(own) / "plugin.json";
    ChildJob job;
    job.argv = {self.string(), "describe", plugin.string(), "--out", out.string()};
    job.log = fs::path(own) / "describe.log";
    job.timeout = std::chrono::milliseconds(int64_t(timeout_seconds * 1000));
    ChildOutcome outcome;
    run_children({job}, 1, [&](size_t, const ChildOutcome& o) { outcome = o; });
    fs::rename(job.log, work_directory / "describe.log", ec);  // kept for whoever debugs it
    if (!outcome.started) return make_error(ErrorCode::Io, outcome.message);
    const bool described =
        !outcome.timed_out && !outcome.signal && outcome.exit_code == 0 && fs::exists(out, ec);
    if (!described) {
        const std::string why =
            describe_failure(outcome, tail_of_file(work_directory / "describe.log", 4000));
        // The host's own refusal names the plugin file already: name it once, not nested.
        std::string reason = why;
        if (reason.rfind(plugin.string() + ": ", 0) == 0)
            reason.erase(0, plugin.string().size() + 2);
        return make_error(ErrorCode::InvalidInput, fmt::format("{}: cannot describe the plugin: {}",
                                                               plugin.string(), reason));
    }
    // The child ran plugin code, so what it wrote is read like any untrusted input.
    auto parsed = read_json_file(out, kMaxHarnessFileBytes, "a harness file");
    if (!parsed) return parsed.error();
    return plugin_info_from_json(*parsed, out.string());
}

}  // namespace acetate::harness
