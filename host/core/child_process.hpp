#pragma once
// Child processes with a time limit, several at once: how the harness isolates every case
// (clap-validator's model). A crash kills only the child; a hang is killed at the limit.
//
// The limit counts the child's CPU time, not the clock: on a loaded machine (CI running other
// jobs beside the harness) a correct case gets less of the CPU per second and would otherwise
// be killed for the load, not for itself. A child that waits without using the CPU (a plugin
// that sleeps or blocks) is killed at `wall_factor` times the limit on the clock.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace acetate {

struct ChildJob {
    std::vector<std::string> argv;  // argv[0] is the executable's path
    std::filesystem::path log;      // the child's stdout and stderr go here
    // Killed once it has used this much CPU time (all its threads) and run this long, or
    // when it has run `wall_factor` times this long whatever it used.
    std::chrono::milliseconds timeout{60000};
    double wall_factor = 4;
    // Spawned afresh even when a fork server is given: a child that must not inherit what the
    // server loaded (a case run without the validation layer).
    bool fresh_process = false;
};

struct ChildOutcome {
    bool started = false;    // false: could not spawn (message says why)
    bool timed_out = false;  // killed at the limit
    int exit_code = -1;      // when it exited
    int signal = 0;          // when a signal ended it (other than our kill at the limit)
    double seconds = 0;      // on the clock
    double cpu_seconds = 0;  // user and system time of all its threads (last seen while running)
    std::string message;     // "exit 1", "killed by SIGSEGV", "no result after 60 s", ...
};

class ForkServer;

// Runs `jobs`, at most `parallel` at a time, calling `done(index, outcome)` as each finishes
// (on this thread, in completion order). With a `server` (fork_server.hpp: every job's argv[0]
// must be the server's own program), each child is forked from it instead of spawned; where
// the server cannot, the job is spawned as without one.
void run_children(const std::vector<ChildJob>& jobs, unsigned parallel,
                  const std::function<void(size_t, const ChildOutcome&)>& done,
                  ForkServer* server = nullptr);

// The CPU time (user and system, all threads) process `pid` has used so far, in seconds;
// negative when /proc cannot tell.
double process_cpu_seconds(int pid);

// The last `max_bytes` of a text file (a child's log), "" if unreadable.
std::string tail_of_file(const std::filesystem::path& file, size_t max_bytes);

// The last non-empty line of a child's log: its one-line error, when it wrote one.
std::string last_line(const std::string& text);
// The last (up to) 3 non-empty lines, each cut to 160 characters, joined with " | ".
std::string last_lines(const std::string& text);
// `what`, then "; last log lines: ..." when the log has any.
std::string with_log(const std::string& what, const std::string& log);
// How the plugin ended a child it took down while `doing` something: "the plugin called
// exit(0) during the case", "... exited with status 7 ...", "... crashed ... (killed by
// SIGSEGV)".
std::string plugin_ended(const ChildOutcome& outcome, const std::string& doing);

}  // namespace acetate
