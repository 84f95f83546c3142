#pragma once
// A fork server: how the harness starts a case's child in a fraction of the time an exec takes.
//
// Starting a program here costs about 0.3 s before main() (the dynamic loader binding the 260
// libraries OpenImageIO brings, their static initializers), more than half of what a typical
// case costs. The server is the same program, started once per batch and never doing any work
// of its own; each child is forked from it, so it begins with every library loaded and bound,
// but is still a fresh process: nothing of one case reaches the next, and a crash, exit or
// hang takes down only that child.
//
// The children stay the caller's own: the server forks twice and the middle process exits, so
// each child is reparented to the caller (a child subreaper, PR_SET_CHILD_SUBREAPER), which
// waits for, times and kills it exactly as one it spawned itself (child_process.hpp).
//
// Forking without exec has two hazards, both handled in the child: threads of the server do not
// exist there (OpenImageIO's dependencies start an idle thread pool at load), so the child
// never runs the server's exit handlers (exit() in the child, by the program or a plugin, ends
// it at once with its status, after flushing stdio); and descriptors of the server are closed
// (stdin is /dev/null, stdout and stderr the job's log), as an exec'd child would have them.

#include <sys/types.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace acetate {

// The server's side: reads requests on standard input until end of file; for each, forks a
// child that runs `run(argc, argv)` with the request's arguments and exits with its result.
// The program calls this from main() when started as its server.
//
// `prepare`, when given, runs once before the first request: work every child would do the
// same way at its start (loading libraries, warming caches), done once so each child begins
// after it. It must leave no thread behind, as a child would not have it: when it fails, or
// the server has more threads after it than before, the server says why on standard error
// and ends, and the caller spawns its children itself.
int serve_forks(const std::function<int(int argc, char** argv)>& run,
                const std::function<bool(std::string& error)>& prepare = {});

class ForkServer {
  public:
    // Starts `server_argv` (a program that calls serve_forks) and makes this process the
    // subreaper of the children it will fork. Null, with `error` saying why, when it cannot
    // (the caller then spawns its children itself).
    static std::unique_ptr<ForkServer> start(const std::vector<std::string>& server_argv,
                                             std::string& error);
    ~ForkServer();  // the server sees end of file, exits, and is reaped
    ForkServer(const ForkServer&) = delete;
    ForkServer& operator=(const ForkServer&) = delete;

    // A child running `argv` (argv[0] is ignored: the server's program runs it), its stdout and
    // stderr in `log`; its pid, now this process's child. -1 and `error` when the server could
    // not start it (the server is then not used again).
    pid_t launch(const std::vector<std::string>& argv, const std::string& log, std::string& error);
    pid_t pid() const { return pid_; }  // the server's own

  private:
    ForkServer() = default;
    int socket_ = -1;
    pid_t pid_ = -1;
    bool broken_ = false;
};

}  // namespace acetate
