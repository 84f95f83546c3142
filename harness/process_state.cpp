#include "process_state.hpp"

#include <dirent.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cfenv>
#include <clocale>
#include <cstdlib>
#include <cstring>
#include <locale>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

extern char** environ;

namespace acetate::harness {
namespace {

std::string rounding_name(int mode) {
    switch (mode) {
        case FE_TONEAREST:
            return "to nearest";
        case FE_TOWARDZERO:
            return "toward zero";
        case FE_UPWARD:
            return "upward";
        case FE_DOWNWARD:
            return "downward";
        default:
            return fmt::format("mode {}", mode);
    }
}

std::string link_target(const std::string& path) {
    char buffer[4096];
    const ssize_t n = ::readlink(path.c_str(), buffer, sizeof buffer - 1);
    return n < 0 ? std::string() : std::string(buffer, size_t(n));
}

// The folders the Vulkan driver's shader cache writes to: its own thread opens and closes files
// there at any moment, plugin call or not, so they are not the plugin's.
std::vector<std::string> shader_cache_folders() {
    std::vector<std::string> out;
    auto add = [&](const char* variable, const char* below) {
        if (const char* value = std::getenv(variable); value && *value)
            out.push_back(std::string(value) + below);
    };
    add("MESA_SHADER_CACHE_DIR", "");
    add("XDG_CACHE_HOME", "/mesa_shader_cache");
    add("HOME", "/.cache/mesa_shader_cache");
    return out;
}

// Every open descriptor but the one listing them, those of the shader cache's thread, and
// those closed while being listed (another thread's, gone before they could be read).
std::map<int, std::string> open_descriptors() {
    static const std::vector<std::string> cache_folders = shader_cache_folders();
    std::map<int, std::string> out;
    DIR* dir = ::opendir("/proc/self/fd");
    if (!dir) return out;
    const int listing = ::dirfd(dir);
    while (const dirent* entry = ::readdir(dir)) {
        if (entry->d_name[0] == '.') continue;
        const int fd = std::atoi(entry->d_name);
        if (fd == listing) continue;
        const std::string target = link_target(std::string("/proc/self/fd/") + entry->d_name);
        if (target.empty()) continue;
        bool cache = false;
        for (const std::string& folder : cache_folders) cache |= target.rfind(folder + "/", 0) == 0;
        if (!cache) out[fd] = target;
    }
    ::closedir(dir);
    return out;
}

int thread_count() {
    int count = 0;
    DIR* dir = ::opendir("/proc/self/task");
    if (!dir) return 0;
    while (const dirent* entry = ::readdir(dir))
        if (entry->d_name[0] != '.') ++count;
    ::closedir(dir);
    return count;
}

template <class Map, class Describe>
void compare_maps(const Map& before, const Map& after, const std::string& what,
                  const Describe& describe, std::vector<std::string>& out) {
    for (const auto& [key, value] : before) {
        auto found = after.find(key);
        if (found == after.end())
            out.push_back(fmt::format("{}: {} removed (was {})", what, describe(key), value));
        else if (found->second != value)
            out.push_back(fmt::format("{}: {} changed from {} to {}", what, describe(key), value,
                                      found->second));
    }
    for (const auto& [key, value] : after)
        if (!before.count(key))
            out.push_back(fmt::format("{}: {} added ({})", what, describe(key), value));
}

}  // namespace

ProcessState capture_process_state() {
    ProcessState s;
    s.rounding = std::fegetround();
#if defined(__x86_64__)
    // FTZ (bit 15), DAZ (bit 6) and the exception masks (bits 7-12); not the sticky flags,
    // which any arithmetic sets.
    s.float_control = _mm_getcsr() & (0x8000u | 0x0040u | 0x1F80u);
#endif
    s.trapped = fegetexcept();
    for (int sig = 1; sig < NSIG; ++sig) {
        if (sig == SIGKILL || sig == SIGSTOP) continue;
        struct sigaction action {};
        if (::sigaction(sig, nullptr, &action) != 0) continue;
        const void* handler = (action.sa_flags & SA_SIGINFO)
                                  ? reinterpret_cast<const void*>(action.sa_sigaction)
                                  : reinterpret_cast<const void*>(action.sa_handler);
        if (action.sa_handler == SIG_DFL && !(action.sa_flags & SA_SIGINFO)) continue;
        s.signals[sig] = action.sa_handler == SIG_IGN
                             ? std::string("ignored")
                             : fmt::format("handler {} flags {:#x}", handler, action.sa_flags);
    }
    sigset_t blocked;
    if (::pthread_sigmask(SIG_BLOCK, nullptr, &blocked) == 0)
        for (int sig = 1; sig < NSIG; ++sig)
            if (sigismember(&blocked, sig) == 1)
                s.blocked += fmt::format("{}{}", s.blocked.empty() ? "" : " ", sig);
    for (char** e = environ; e && *e; ++e) {
        const char* equals = std::strchr(*e, '=');
        if (equals)
            s.environment[std::string(*e, size_t(equals - *e))] = equals + 1;
        else
            s.environment[*e] = "";
    }
    s.descriptors = open_descriptors();
    s.threads = thread_count();
    char folder[4096];
    if (::getcwd(folder, sizeof folder)) s.working_folder = folder;
    const mode_t mask = ::umask(0);
    ::umask(mask);
    s.umask = uint32_t(mask);
    const char* c_locale = std::setlocale(LC_ALL, nullptr);
    s.locale = fmt::format("{} / {}", c_locale ? c_locale : "?", std::locale().name());
    return s;
}

std::vector<std::string> process_differences(const ProcessState& before,
                                             const ProcessState& after) {
    std::vector<std::string> out;
    if (before.rounding != after.rounding)
        out.push_back(fmt::format("rounding mode: {} -> {}", rounding_name(before.rounding),
                                  rounding_name(after.rounding)));
    if (before.float_control != after.float_control) {
        const uint32_t changed = before.float_control ^ after.float_control;
        const auto bit = [&](uint32_t mask, const char* name) {
            if (changed & mask)
                out.push_back(fmt::format("{}: {} -> {}", name,
                                          (before.float_control & mask) ? "on" : "off",
                                          (after.float_control & mask) ? "on" : "off"));
        };
        bit(0x8000u, "flush-to-zero (MXCSR FTZ)");
        bit(0x0040u, "denormals-are-zero (MXCSR DAZ)");
        if (changed & 0x1F80u)
            out.push_back(fmt::format("floating-point exception masks (MXCSR): {:#x} -> {:#x}",
                                      before.float_control & 0x1F80u,
                                      after.float_control & 0x1F80u));
    }
    if (before.trapped != after.trapped)
        out.push_back(
            fmt::format("trapped floating-point exceptions (feenableexcept): {:#x} -> "
                        "{:#x}",
                        before.trapped, after.trapped));
    compare_maps(
        before.signals, after.signals, "signal disposition",
        [](int sig) {
            const char* name = sigabbrev_np(sig);
            return name ? fmt::format("SIG{}", name) : fmt::format("signal {}", sig);
        },
        out);
    if (before.blocked != after.blocked)
        out.push_back(fmt::format("blocked signals: [{}] -> [{}]", before.blocked, after.blocked));
    // Names only: a value may be a secret, and the report is shared.
    for (const auto& [name, value] : before.environment) {
        auto found = after.environment.find(name);
        if (found == after.environment.end())
            out.push_back(fmt::format("environment: {} unset", name));
        else if (found->second != value)
            out.push_back(fmt::format("environment: {} changed", name));
    }
    for (const auto& [name, value] : after.environment)
        if (!before.environment.count(name))
            out.push_back(fmt::format("environment: {} set", name));
    compare_maps(
        before.descriptors, after.descriptors, "open descriptor",
        [](int fd) { return std::to_string(fd); }, out);
    if (before.threads != after.threads)
        out.push_back(fmt::format("threads: {} -> {}", before.threads, after.threads));
    if (before.working_folder != after.working_folder)
        out.push_back(
            fmt::format("working folder: {} -> {}", before.working_folder, after.working_folder));
    if (before.umask != after.umask)
        out.push_back(fmt::format("umask: {:03o} -> {:03o}", before.umask, after.umask));
    if (before.locale != after.locale)
        out.push_back(fmt::format("locale: {} -> {}", before.locale, after.locale));
    return out;
}

}  // namespace acetate::harness
