#include "core/child_process.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/fork_server.hpp"

extern char** environ;

namespace acetate {
namespace {

using Clock = std::chrono::steady_clock;

struct Running {
    size_t index = 0;
    pid_t pid = 0;
    Clock::time_point start;
    double cpu_seconds = 0;  // last seen
};

ChildOutcome spawn(const ChildJob& job, pid_t& pid) {
    ChildOutcome outcome;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, job.log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::vector<char*> argv;
    for (const std::string& arg : job.argv) argv.push_back(const_cast<char*>(arg.c_str()));
    argv.push_back(nullptr);
    const int error = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (error) {
        outcome.message = fmt::format("cannot start {}: {}", job.argv[0], std::strerror(error));
        return outcome;
    }
    outcome.started = true;
    return outcome;
}

// From the fork server when there is one, the job allows it and the server can; spawned
// otherwise.
ChildOutcome launch(const ChildJob& job, ForkServer* server, pid_t& pid) {
    if (server && !job.fresh_process) {
        std::string error;
        pid = server->launch(job.argv, job.log.string(), error);
        if (pid > 0) {
            ChildOutcome outcome;
            outcome.started = true;
            return outcome;
        }
    }
    return spawn(job, pid);
}

ChildOutcome finished(int status, double seconds) {
    ChildOutcome outcome;
    outcome.started = true;
    outcome.seconds = seconds;
    if (WIFEXITED(status)) {
        outcome.exit_code = WEXITSTATUS(status);
        outcome.message = fmt::format("exit {}", outcome.exit_code);
    } else if (WIFSIGNALED(status)) {
        outcome.signal = WTERMSIG(status);
        const char* name = sigabbrev_np(outcome.signal);
        outcome.message =
            fmt::format("killed by SIG{} ({})", name ? name : "?", strsignal(outcome.signal));
    }
    return outcome;
}

}  // namespace

void run_children(const std::vector<ChildJob>& jobs, unsigned parallel,
                  const std::function<void(size_t, const ChildOutcome&)>& done,
                  ForkServer* server) {
    parallel = std::max(1u, parallel);
    std::vector<Running> running;
    size_t next = 0;
    while (next < jobs.size() || !running.empty()) {
        while (next < jobs.size() && running.size() < parallel) {
            pid_t pid = 0;
            ChildOutcome outcome = launch(jobs[next], server, pid);
            if (!outcome.started)
                done(next, outcome);
            else
                running.push_back({next, pid, Clock::now()});
            ++next;
        }
        bool reaped = false;
        for (size_t i = 0; i < running.size();) {
            Running& r = running[i];
            const double seconds = std::chrono::duration<double>(Clock::now() - r.start).count();
            int status = 0;
            if (waitpid(r.pid, &status, WNOHANG) == r.pid) {
                const size_t index = r.index;
                ChildOutcome outcome = finished(status, seconds);
                outcome.cpu_seconds = r.cpu_seconds;
                running.erase(running.begin() + i);
                done(index, outcome);
                reaped = true;
                continue;
            }
            const ChildJob& job = jobs[r.index];
            const double limit = std::chrono::duration<double>(job.timeout).count();
            // Unreadable CPU time (no /proc): the clock alone decides.
            bool clock_only = false;
            if (seconds > limit) {
                const double cpu = process_cpu_seconds(r.pid);
                clock_only = cpu < 0;
                if (!clock_only) r.cpu_seconds = cpu;
            }
            const bool used_its_share = clock_only || r.cpu_seconds > limit;
            const bool waited_too_long = seconds > limit * std::max(1.0, job.wall_factor);
            if (seconds > limit && (used_its_share || waited_too_long)) {
                kill(r.pid, SIGKILL);
                waitpid(r.pid, &status, 0);
                ChildOutcome outcome;
                outcome.started = true;
                outcome.timed_out = true;
                outcome.seconds = seconds;
                outcome.cpu_seconds = r.cpu_seconds;
                outcome.message =
                    used_its_share ? fmt::format(
                                         "no result after {:.0f} s of CPU time ({:.1f} s on the "
                                         "clock): killed",
                                         limit, seconds)
                                   : fmt::format(
                                         "no result after {:.0f} s on the clock ({:.1f} s of CPU "
                                         "time: waiting, not computing): killed",
                                         seconds, r.cpu_seconds);
                const size_t index = r.index;
                running.erase(running.begin() + i);
                done(index, outcome);
                reaped = true;
                continue;
            }
            ++i;
        }
        if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

double process_cpu_seconds(int pid) {
    // /proc/<pid>/stat: "pid (comm) state ..."; comm may hold spaces and parentheses, so the
    // fields are counted from the last ')'. utime and stime are fields 14 and 15, in clock
    // ticks, and cover every thread of the process.
    std::ifstream in(fmt::format("/proc/{}/stat", pid));
    std::string text;
    if (!std::getline(in, text)) return -1;
    const size_t close = text.rfind(')');
    if (close == std::string::npos) return -1;
    std::istringstream fields(text.substr(close + 1));
    std::string field;
    unsigned long long utime = 0, stime = 0;
    for (int n = 3; n <= 15 && fields >> field; ++n) {
        if (n == 14) utime = std::strtoull(field.c_str(), nullptr, 10);
        if (n == 15) stime = std::strtoull(field.c_str(), nullptr, 10);
    }
    if (!fields) return -1;
    const long ticks = sysconf(_SC_CLK_TCK);
    return ticks > 0 ? double(utime + stime) / double(ticks) : -1;
}

std::string tail_of_file(const std::filesystem::path& file, size_t max_bytes) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return {};
    std::ostringstream all;
    all << in.rdbuf();
    std::string text = all.str();
    if (text.size() > max_bytes) text = "..." + text.substr(text.size() - max_bytes);
    return text;
}

// The last non-empty line of a child's log: its one-line error, when it wrote one.
std::string last_line(const std::string& text) {
    std::istringstream in(text);
    std::string line, last;
    while (std::getline(in, line))
        if (!line.empty()) last = line;
    return last;
}

// The last (up to) 3 non-empty lines of a child's log, each cut to 160 characters, joined with
// " | ": what the plugin or the host printed just before the plugin took the child down, which
// is often the cause. One line, so the case's message stays one line.
std::string last_lines(const std::string& text) {
    constexpr size_t kCount = 3, kWidth = 160;
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        const size_t first = line.find_first_not_of(" \t\r"), last = line.find_last_not_of(" \t\r");
        if (first == std::string::npos) continue;
        line = line.substr(first, last - first + 1);
        // In place: GCC 12 reports a false -Warray-bounds for substr(...) + "..." here.
        if (line.size() > kWidth) line.replace(kWidth, std::string::npos, "...");
        lines.push_back(std::move(line));
    }
    std::string out;
    for (size_t i = lines.size() > kCount ? lines.size() - kCount : 0; i < lines.size(); ++i)
        out += (out.empty() ? "" : " | ") + lines[i];
    return out;
}

// `what`, then the log's last lines when the child printed any.
std::string with_log(const std::string& what, const std::string& log) {
    const std::string lines = last_lines(log);
    return lines.empty() ? what : fmt::format("{}; last log lines: {}", what, lines);
}

// How the plugin ended a child it took down, `doing` something: "the plugin called exit(0)
// during the case", "... exited with status 7 ...", "... crashed during the case (killed by
// SIGSEGV)". exit(0) is named as such: a reader would otherwise take status 0 for success.
std::string plugin_ended(const ChildOutcome& outcome, const std::string& doing) {
    if (outcome.signal) {
        const char* name = sigabbrev_np(outcome.signal);
        return fmt::format(
            "the plugin crashed {} (killed by {})", doing,
            name ? fmt::format("SIG{}", name) : fmt::format("signal {}", outcome.signal));
    }
    if (outcome.exit_code == 0) return fmt::format("the plugin called exit(0) {}", doing);
    return fmt::format("the plugin exited with status {} {}", outcome.exit_code, doing);
}

}  // namespace acetate
