#pragma once
// What a plugin call may change in the process it runs in, and must leave as it found it
// (docs/contract.md, rule 7): the floating-point environment (rounding mode, flush-to-zero,
// denormals-are-zero, trapped exceptions), signal dispositions and the signal mask, the
// environment variables, the open file descriptors, the number of threads, the working
// folder, the umask and the locale. The harness takes one snapshot before and one after each
// plugin call (process_hygiene.hpp) and names every difference.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace acetate::harness {

struct ProcessState {
    int rounding = 0;                    // fegetround()
    uint32_t float_control = 0;          // x86-64: MXCSR's FTZ, DAZ and exception masks; else 0
    int trapped = 0;                     // fegetexcept(): exceptions that raise SIGFPE
    std::map<int, std::string> signals;  // signal -> "handler flags", only those not default
    std::string blocked;                 // the calling thread's blocked signals, as a list
    std::map<std::string, std::string> environment;
    std::map<int, std::string> descriptors;  // fd -> what it is open on
    int threads = 0;
    std::string working_folder;
    uint32_t umask = 0;
    std::string locale;  // setlocale(LC_ALL, NULL), then the C++ global locale's name
};

// This process, now. Reads /proc/self; each part that cannot be read is left empty (and so
// compares equal to itself).
ProcessState capture_process_state();

// Every difference from `before` to `after`, one line each ("rounding mode: to nearest ->
// toward zero", "environment: LC_ALL set" (names, never values), "descriptor 7 opened on /tmp/x"),
// in the order of the fields above; empty when the process is as it was.
std::vector<std::string> process_differences(const ProcessState& before, const ProcessState& after);

}  // namespace acetate::harness
