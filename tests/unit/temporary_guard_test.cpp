// TemporaryGuard: a SIGINT or SIGTERM while a named temporary is guarded removes it, and the
// signal still ends the process as it would have (or reaches the program's own handler). Each
// case runs in a forked child, which the signal ends.
#include "core/temporary_guard.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

// Runs `body` in a child process and returns its wait status.
int in_child(const std::function<void()>& body) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        body();
        ::_exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return status;
}

fs::path make_temporary(const fs::path& dir) {
    const fs::path file = dir / "out.tmp-1-0.exr";
    std::ofstream(file) << "half an image";
    return file;
}

TEST(TemporaryGuard, SigtermAndSigintRemoveAGuardedTemporary) {
    for (int signal : {SIGTERM, SIGINT}) {
        const fs::path file = make_temporary(test::scratch_dir());
        const int status = in_child([&] {
            TemporaryGuard guard(file);
            if (!guard.guarded()) ::_exit(3);
            ::raise(signal);
            ::_exit(4);  // not reached: the signal ends the child
        });
        ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << signal << ", status " << status;
        EXPECT_EQ(WTERMSIG(status), signal);
        EXPECT_FALSE(fs::exists(file)) << "signal " << signal;
    }
}

TEST(TemporaryGuard, AFileNoLongerGuardedStays) {
    const fs::path file = make_temporary(test::scratch_dir());
    const int status = in_child([&] {
        { TemporaryGuard guard(file); }
        ::raise(SIGTERM);
    });
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_TRUE(fs::exists(file)) << "only guarded names are removed";
}

TEST(TemporaryGuard, TheProgramsOwnHandlerStillRuns) {
    const fs::path file = make_temporary(test::scratch_dir());
    const int status = in_child([&] {
        ::signal(SIGTERM, [](int) { ::_exit(42); });
        TemporaryGuard guard(file);
        ::raise(SIGTERM);
    });
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 42);
    EXPECT_FALSE(fs::exists(file));
}

}  // namespace
}  // namespace acetate
