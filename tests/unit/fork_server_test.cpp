// The fork server (host/core/fork_server.hpp) through run_children, as the harness uses it:
// children forked from a server that holds the host library's libraries and their idle threads
// exit with their own status or signal, are timed out and killed like spawned ones, write only
// to their log, hold no descriptor but stdin (/dev/null), stdout and stderr, are fresh processes
// (a new pid each), and `exit()` in a child ends it at once instead of hanging on the server's
// exit handlers. A server that is gone falls back to spawning. No device.

#include "core/fork_server.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/child_process.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;
using ::acetate::test::read_file;
namespace fs = std::filesystem;

struct Ran {
    ChildOutcome outcome;
    std::string log;
};

// Runs each command line of `commands` (arguments of the probe) as a child, two at a time,
// through `server` (or spawned, when null), logs in `dir`; their outcomes and logs in order.
// The jobs at the indices in `fresh` ask to be spawned afresh whatever the server.
std::vector<Ran> run_probe(const fs::path& dir,
                           const std::vector<std::vector<std::string>>& commands,
                           ForkServer* server, std::chrono::milliseconds timeout,
                           const std::set<size_t>& fresh = {}) {
    std::vector<ChildJob> jobs;
    for (size_t i = 0; i < commands.size(); ++i) {
        ChildJob job;
        job.argv = {ACETATE_FORK_SERVER_PROBE};
        job.argv.insert(job.argv.end(), commands[i].begin(), commands[i].end());
        job.log = dir / ("child" + std::to_string(i) + ".log");
        job.timeout = timeout;
        job.fresh_process = fresh.count(i) > 0;
        jobs.push_back(job);
    }
    std::vector<Ran> ran(jobs.size());
    run_children(
        jobs, 2, [&](size_t i, const ChildOutcome& o) { ran[i].outcome = o; }, server);
    for (size_t i = 0; i < jobs.size(); ++i) ran[i].log = read_file(jobs[i].log);
    return ran;
}

// A server; with `prepare`, its preparation is that one (FORK_PROBE_PREPARE in the probe).
std::unique_ptr<ForkServer> start_server(const char* prepare = nullptr) {
    std::string error;
    if (prepare) ::setenv("FORK_PROBE_PREPARE", prepare, 1);
    auto server = ForkServer::start({ACETATE_FORK_SERVER_PROBE, "fork-server"}, error);
    ::unsetenv("FORK_PROBE_PREPARE");
    EXPECT_TRUE(server) << error;
    return server;
}

TEST(ForkServer, ChildrenEndWithTheirOwnStatusOrSignal) {
    auto server = start_server();
    ASSERT_TRUE(server);
    const auto ran = run_probe(test::scratch_dir(),
                               {{"print", "hello"},
                                {"return", "7"},
                                {"exit", "5"},
                                {"raise", std::to_string(SIGSEGV)},
                                {"raise", std::to_string(SIGABRT)}},
                               server.get(), std::chrono::seconds(20));
    EXPECT_EQ(ran[0].outcome.exit_code, 0) << ran[0].outcome.message;
    EXPECT_EQ(ran[0].log, "hello\n");
    EXPECT_EQ(ran[1].outcome.exit_code, 7) << ran[1].outcome.message;
    // exit() would run the server's exit handlers, which join threads the child does not have.
    EXPECT_FALSE(ran[2].outcome.timed_out) << "exit() in a forked child hung";
    EXPECT_EQ(ran[2].outcome.exit_code, 5) << ran[2].outcome.message;
    EXPECT_EQ(ran[3].outcome.signal, SIGSEGV) << ran[3].outcome.message;
    EXPECT_EQ(ran[4].outcome.signal, SIGABRT) << ran[4].outcome.message;
}

TEST(ForkServer, AChildPastItsLimitIsKilled) {
    auto server = start_server();
    ASSERT_TRUE(server);
    const auto start = std::chrono::steady_clock::now();
    const auto ran = run_probe(test::scratch_dir(), {{"sleep", "60"}, {"print", "after"}},
                               server.get(), std::chrono::milliseconds(1500));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_TRUE(ran[0].outcome.timed_out) << ran[0].outcome.message;
    EXPECT_EQ(ran[1].outcome.exit_code, 0) << ran[1].outcome.message;
    EXPECT_LT(seconds, 10.0) << "the sleeping child was waited for, not killed";
}

// The limit counts CPU time (a loaded machine slows a correct child without failing it): a
// child that computes is killed once it has used the limit; one that waits past the limit on
// the clock without computing finishes, and one that waits far longer is killed at
// wall_factor times the limit. (Spawned children are watched by the same loop.)
TEST(ChildLimits, TheLimitCountsCpuTimeAndTheClockIsABackstop) {
    auto server = start_server();
    ASSERT_TRUE(server);
    const auto ran =
        run_probe(test::scratch_dir(), {{"spin", "60"}, {"sleep", "2.5"}, {"sleep", "60"}},
                  server.get(), std::chrono::milliseconds(1000));
    const ChildOutcome& spin = ran[0].outcome;
    EXPECT_TRUE(spin.timed_out) << spin.message;
    EXPECT_GE(spin.cpu_seconds, 1.0) << spin.message;
    EXPECT_TRUE(contains(spin.message, "no result after 1 s of CPU time")) << spin.message;
    // Past the 1 s limit on the clock, but it used almost no CPU: not killed.
    EXPECT_FALSE(ran[1].outcome.timed_out) << ran[1].outcome.message;
    EXPECT_EQ(ran[1].outcome.exit_code, 0) << ran[1].outcome.message;
    const ChildOutcome& waits = ran[2].outcome;
    EXPECT_TRUE(waits.timed_out) << waits.message;
    EXPECT_GE(waits.seconds, 4.0) << "killed before wall_factor (4) times the limit";
    EXPECT_LT(waits.seconds, 8.0) << waits.message;
    EXPECT_TRUE(contains(waits.message, "waiting, not computing")) << waits.message;
}

TEST(ForkServer, ChildrenAreFreshProcessesWithOnlyTheirLog) {
    auto server = start_server();
    ASSERT_TRUE(server);
    const fs::path dir = test::scratch_dir();
    const auto ran = run_probe(dir,
                               {{"fds"},
                                {"mark", (dir / "a").string()},
                                {"mark", (dir / "b").string()},
                                {"mark", (dir / "c").string()}},
                               server.get(), std::chrono::seconds(20));
    ASSERT_EQ(ran[0].outcome.exit_code, 0) << ran[0].outcome.message << ran[0].log;
    std::set<std::string> fds;
    std::istringstream lines(ran[0].log);
    for (std::string tag, fd, target; lines >> tag >> fd >> target;) fds.insert(fd + " " + target);
    const std::string log = ran[0].log;
    EXPECT_EQ(fds.size(), 3u) << "only stdin, stdout and stderr are open:\n" << log;
    EXPECT_TRUE(contains(log, "fd 0 /dev/null")) << log;
    EXPECT_TRUE(contains(log, "fd 1 " + (dir / "child0.log").string())) << log;
    EXPECT_TRUE(contains(log, "fd 2 " + (dir / "child0.log").string())) << log;
    std::set<std::string> pids;
    for (const char* name : {"a", "b", "c"}) pids.insert(read_file(dir / name));
    EXPECT_EQ(pids.size(), 3u) << "each child is its own process";
}

TEST(ForkServer, ChildrenWithoutAServerAreSpawnedAlike) {
    // The control: the same commands spawned give the same outcomes.
    const auto ran = run_probe(test::scratch_dir(), {{"print", "hello"}, {"exit", "5"}, {"fds"}},
                               nullptr, std::chrono::seconds(20));
    EXPECT_EQ(ran[0].log, "hello\n");
    EXPECT_EQ(ran[1].outcome.exit_code, 5);
    EXPECT_TRUE(contains(ran[2].log, "fd 0")) << ran[2].log;
}

TEST(ForkServer, AServerThatIsGoneFallsBackToSpawning) {
    auto server = start_server();
    ASSERT_TRUE(server);
    // Kill the server behind its back: the next launch finds no answer and spawns instead.
    const fs::path dir = test::scratch_dir();
    const auto first =
        run_probe(dir, {{"print", "before"}}, server.get(), std::chrono::seconds(20));
    ASSERT_EQ(first[0].outcome.exit_code, 0);
    ASSERT_EQ(::kill(server->pid(), SIGKILL), 0);
    const auto ran = run_probe(test::scratch_dir(), {{"print", "still"}}, server.get(),
                               std::chrono::seconds(20));
    EXPECT_EQ(ran[0].outcome.exit_code, 0) << ran[0].outcome.message;
    EXPECT_EQ(ran[0].log, "still\n");
}

TEST(ForkServer, ChildrenStartAfterTheServersPreparation) {
    auto server = start_server("work");
    ASSERT_TRUE(server);
    const auto ran = run_probe(test::scratch_dir(), {{"prepared"}, {"prepared"}}, server.get(),
                               std::chrono::seconds(20));
    EXPECT_EQ(ran[0].log, "prepared\n");
    EXPECT_EQ(ran[1].log, "prepared\n");
}

TEST(ForkServer, AJobThatAsksForAFreshProcessIsSpawned) {
    // A case without the validation layer must not inherit the layer the server loaded.
    auto server = start_server("work");
    ASSERT_TRUE(server);
    const auto ran = run_probe(test::scratch_dir(), {{"prepared"}, {"prepared"}}, server.get(),
                               std::chrono::seconds(20), {1});
    EXPECT_EQ(ran[0].log, "prepared\n");
    EXPECT_EQ(ran[1].log, "not prepared\n");
    EXPECT_EQ(ran[1].outcome.exit_code, 0) << ran[1].outcome.message;
}

TEST(ForkServer, APreparationThatFailsOrLeavesAThreadIsNotUsed) {
    // A thread the preparation started would be missing in every child: the server refuses to
    // serve, and the children are spawned, unprepared but whole.
    for (const char* how : {"thread", "fail"}) {
        auto server = start_server(how);
        ASSERT_TRUE(server);
        const auto ran = run_probe(test::scratch_dir(), {{"prepared"}, {"print", "still"}},
                                   server.get(), std::chrono::seconds(20));
        EXPECT_EQ(ran[0].log, "not prepared\n") << how;
        EXPECT_EQ(ran[1].outcome.exit_code, 0) << how << ": " << ran[1].outcome.message;
        EXPECT_EQ(ran[1].log, "still\n") << how;
    }
}

}  // namespace
}  // namespace acetate
