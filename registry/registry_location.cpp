#include "registry_location.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <system_error>

namespace acetate {
namespace fs = std::filesystem;

namespace {

// The running program's own file (argv[0] may be relative or a link).
fs::path program_file() {
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : exe;
}

fs::path same_file_form(const fs::path& p) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(p, ec);
    return ec ? p.lexically_normal() : canonical;
}

// The installation this code was installed with: PREFIX for PREFIX/<libdir>/libacetate-host.so,
// the library this file is compiled into. Found from the library rather than the program, so a
// program that embeds the host from anywhere (not only PREFIX/bin/acetate) finds the installed
// keys and sign-offs.
fs::path install_prefix() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&install_prefix), &info) && info.dli_fname) {
        fs::path prefix = same_file_form(info.dli_fname).parent_path();
        // One folder up per component of the libdir ("lib", or "lib/x86_64-linux-gnu").
        const fs::path libdir = ACETATE_INSTALL_LIBDIR;
        for (auto part = libdir.begin(); part != libdir.end(); ++part)
            prefix = prefix.parent_path();
        return prefix;
    }
    return program_file().parent_path().parent_path();  // PREFIX for PREFIX/bin/program
}

}  // namespace

bool running_from_build_tree() {
    // Build-tree programs live one folder below the build root (build/host/acetate,
    // build/harness/acetate-harness); an installed copy in PREFIX/bin does not, even when the
    // prefix itself lies inside the build tree (as in the install test).
    const fs::path exe = program_file();
    return !exe.empty() &&
           same_file_form(exe.parent_path().parent_path()) == same_file_form(ACETATE_BUILD_DIR);
}

fs::path default_registry_path() {
    if (running_from_build_tree()) return fs::path(ACETATE_BUILD_DIR) / "validation/registry.json";
    if (const char* data = std::getenv("XDG_DATA_HOME");
        data && *data && fs::path(data).is_absolute())
        return fs::path(data) / "acetate/registry.json";
    const char* home = std::getenv("HOME");
    return fs::path(home && *home ? home : "/") / ".local/share/acetate/registry.json";
}

std::optional<fs::path> default_signoffs_path() {
    const fs::path file = running_from_build_tree() ? fs::path(ACETATE_SOURCE_SIGNOFFS)
                                                    : install_prefix() / ACETATE_INSTALL_DATADIR /
                                                          "acetate/validation/signoffs.json";
    std::error_code ec;
    return fs::is_regular_file(file, ec) ? std::optional(file) : std::nullopt;
}

fs::path allowed_signers_path(const std::optional<fs::path>& flag) {
    if (flag && !flag->empty()) return *flag;
    if (const char* env = std::getenv("ACETATE_ALLOWED_SIGNERS"); env && *env) return env;
    return fs::path(running_from_build_tree()
                        ? ACETATE_SOURCE_VALIDATION
                        : install_prefix() / ACETATE_INSTALL_DATADIR / "acetate/validation") /
           "allowed_signers";
}

fs::path references_path(const std::optional<fs::path>& flag) {
    if (flag && !flag->empty()) return *flag;
    if (const char* env = std::getenv("ACETATE_REFERENCES"); env && *env) return env;
    return fs::path(running_from_build_tree()
                        ? ACETATE_SOURCE_VALIDATION
                        : install_prefix() / ACETATE_INSTALL_DATADIR / "acetate/validation") /
           "references";
}

fs::path registry_path(const std::optional<fs::path>& flag) {
    if (flag && !flag->empty()) return *flag;
    if (const char* env = std::getenv("ACETATE_REGISTRY"); env && *env) return env;
    return default_registry_path();
}

fs::path registry_markdown_path(const fs::path& registry) {
    return registry.parent_path() / "VALIDATION-REGISTRY.md";
}

}  // namespace acetate
