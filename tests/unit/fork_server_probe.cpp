// A program for fork_server_test.cpp: started as `fork_server_probe fork-server` it serves
// forks (core/fork_server.hpp); each child runs one command of its arguments:
//   print TEXT   prints TEXT on stdout and returns 0
//   return N     returns N from the child's entry
//   exit N       calls exit(N), as a plugin might
//   raise N      raises signal N
//   sleep S      sleeps S seconds, then returns 0
//   spin S       computes for S seconds of CPU time, then returns 0
//   fds          prints the child's open descriptors and what stdin is, returns 0
//   mark FILE    writes this process's pid into FILE, returns 0
//   prepared     prints "prepared" when the server's preparation ran before this child,
//                "not prepared" when it did not (a spawned child), returns 0
// The server's preparation is chosen by FORK_PROBE_PREPARE: "work" sets the mark `prepared`
// reads, "thread" sets it and leaves a thread running, "fail" fails; unset, there is none.
// It links the host library like acetate-harness, so the server holds the same libraries (and
// the idle threads some of them start at load) that a child must survive without.

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>

#include "core/fork_server.hpp"
#include "scene/image_io.hpp"

namespace {

bool g_prepared = false;

bool prepare(std::string& error) {
    const std::string how = std::getenv("FORK_PROBE_PREPARE");
    g_prepared = true;
    if (how == "thread") std::thread([] { ::pause(); }).detach();
    if (how == "fail") error = "the probe was told to fail";
    return how != "fail";
}

int run_command(int argc, char** argv) {
    if (argc < 2) return 2;
    const std::string what = argv[1];
    const std::string arg = argc > 2 ? argv[2] : "";
    if (what == "print") {
        std::printf("%s\n", arg.c_str());
        return 0;
    }
    if (what == "return") return std::atoi(arg.c_str());
    if (what == "exit") std::exit(std::atoi(arg.c_str()));
    if (what == "raise") {
        ::raise(std::atoi(arg.c_str()));
        return 3;
    }
    if (what == "sleep") {
        std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(arg.c_str())));
        return 0;
    }
    if (what == "spin") {
        const double seconds = std::atof(arg.c_str());
        volatile double sink = 0;
        for (timespec t{}; clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) == 0 &&
                           double(t.tv_sec) + double(t.tv_nsec) * 1e-9 < seconds;)
            for (int i = 0; i < 100000; ++i) sink = sink + 1.0;
        return 0;
    }
    if (what == "fds") {
        // Every open descriptor but the one listing them.
        for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) {
            std::error_code ec;
            const auto target = std::filesystem::read_symlink(entry.path(), ec).string();
            if (target.find("/fd") == std::string::npos || target.rfind("/proc/", 0) != 0)
                std::printf("fd %s %s\n", entry.path().filename().c_str(), target.c_str());
        }
        return 0;
    }
    if (what == "mark") {
        std::ofstream(arg) << ::getpid() << "\n";
        return 0;
    }
    if (what == "prepared") {
        std::printf("%s\n", g_prepared ? "prepared" : "not prepared");
        return 0;
    }
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    // Touch the host library, as acetate-harness does, so it is loaded with all it brings.
    (void)acetate::srgb_to_linear(0.5f);
    if (argc == 2 && std::strcmp(argv[1], "fork-server") == 0)
        return acetate::serve_forks(run_command, std::getenv("FORK_PROBE_PREPARE")
                                                     ? prepare
                                                     : std::function<bool(std::string&)>());
    return run_command(argc, argv);
}
