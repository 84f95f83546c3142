#pragma once
// Child processes with a time limit, several at once: how the harness isolates every case
// (clap-validator's model). A crash kills only the child; a hang is killed at the limit.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace acetate::harness {

struct ChildJob {
    std::vector<std::string> argv;  // argv[0] is the executable's path
    std::filesystem::path log;      // the child's stdout and stderr go here
    std::chrono::milliseconds timeout{60000};
};

struct ChildOutcome {
    bool started = false;    // false: could not spawn (message says why)
    bool timed_out = false;  // killed at the limit
    int exit_code = -1;      // when it exited
    int signal = 0;          // when a signal ended it (other than our kill at the limit)
    double seconds = 0;
    std::string message;  // "exit 1", "killed by SIGSEGV", "no result after 60 s", ...
};

// Runs `jobs`, at most `parallel` at a time, calling `done(index, outcome)` as each finishes
// (on this thread, in completion order).
void run_children(const std::vector<ChildJob>& jobs, unsigned parallel,
                  const std::function<void(size_t, const ChildOutcome&)>& done);

// The last `max_bytes` of a text file (a child's log), "" if unreadable.
std::string tail_of_file(const std::filesystem::path& file, size_t max_bytes);

}  // namespace acetate::harness
