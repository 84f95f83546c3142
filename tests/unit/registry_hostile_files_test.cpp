// The registry file when it is hostile: a FIFO, a device or a folder in its place, a file over
// the size limit, duplicate keys, control characters. Each is refused in one line, unread where
// it can be, and a reader that would block or read without end is caught by running it in a
// bounded child. No GPU needed.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>

#include "core/input_file.hpp"
#include "registry_fixtures.hpp"

namespace acetate {
namespace {

using namespace registry_test;
using ::acetate::test::read_file;

// What Registry::load said, asked in a child process held to `seconds` and to 1 GiB more address
// space than it starts with: a reader that blocks on a FIFO or reads /dev/zero without end is
// killed and fails the test, instead of hanging it or exhausting the machine's memory.
struct BoundedLoad {
    bool finished = false;  // the child exited by itself
    bool loaded = false;    // Registry::load succeeded
    std::string message;    // its error otherwise
    std::string ending;     // how the child ended, for a failing assertion
    double seconds = 0;
};

BoundedLoad load_in_bounded_child(const fs::path& file, unsigned seconds = 10) {
    BoundedLoad outcome;
    int fds[2];
    if (::pipe(fds) != 0) return outcome;
    long pages = 0;
    std::ifstream("/proc/self/statm") >> pages;
    const rlim_t address_space =
        rlim_t(pages) * rlim_t(::sysconf(_SC_PAGESIZE)) + (rlim_t(1) << 30);
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork_child([&] {
        ::close(fds[0]);
        const rlimit limit{address_space, address_space};
        ::setrlimit(RLIMIT_AS, &limit);
        ::alarm(seconds);
        std::string report;
        try {  // nothing may unwind into the child's copy of the test runner
            auto loaded = Registry::load(file);
            report = loaded ? "ok" : "error " + loaded.error().message;
        } catch (const std::exception& e) {
            report = std::string("threw ") + e.what();
        }
        for (size_t done = 0; done < report.size();) {
            const ssize_t n = ::write(fds[1], report.data() + done, report.size() - done);
            if (n <= 0) return 3;
            done += size_t(n);
        }
        return 0;
    });
    ::close(fds[1]);
    std::string report;
    char buffer[4096];
    for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) != 0;) {
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) break;
        report.append(buffer, size_t(n));
    }
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    outcome.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    outcome.finished = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    outcome.ending = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status)) +
                                               (WTERMSIG(status) == SIGALRM ? " (it blocked)" : "")
                                         : "exit status " + std::to_string(WEXITSTATUS(status));
    outcome.loaded = report == "ok";
    if (report.rfind("error ", 0) == 0) outcome.message = report.substr(6);
    if (report.rfind("threw ", 0) == 0) {
        outcome.finished = false;
        outcome.ending += ", the load " + report;
    }
    return outcome;
}

// Found by fuzz_registry: a key holding a newline made a two-line error. Keys and values from
// the file are written with escapes, so every refusal stays one line.
TEST(Registry, ControlCharactersInTheFileStayEscapedInOneLine) {
    auto key = Registry::parse(
        R"({"f\nA\r\u0001": 1, "format": "acetate-registry/1", "plugins": []})", "reg.json");
    ASSERT_FALSE(key.ok());
    EXPECT_EQ(key.error().message,
              "reg.json: unknown field \"f\\nA\\r\\u0001\" (allowed: format, plugins)");
    auto value = Registry::parse(R"({"format": "a\nb", "plugins": []})", "reg.json");
    ASSERT_FALSE(value.ok());
    EXPECT_EQ(value.error().message.find('\n'), std::string::npos) << value.error().message;
    EXPECT_NE(value.error().message.find("a\\nb"), std::string::npos) << value.error().message;
}

TEST_F(RegistryFiles, DuplicateKeysAreRefusedNamingTheField) {
    const std::string good = validated_registry().to_json();
    // A reviewer reading the entry sees binary B first; a parser keeping the last key would
    // validate binary A.
    const std::string field = "\"binary_sha256\": \"" + kBinaryA + "\"";
    const size_t at = good.find(field);
    ASSERT_NE(at, std::string::npos);
    std::string twice = good;
    twice.replace(at, field.size(), "\"binary_sha256\": \"" + kBinaryB + "\",\n    " + field);
    auto parsed = Registry::parse(twice, "reg.json");
    ASSERT_FALSE(parsed) << "accepted; binary A is "
                         << to_string(parsed->binary_stage(kId, kBinaryA));
    EXPECT_EQ(parsed.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(parsed.error().message, "reg.json: plugins[0]: duplicate field \"binary_sha256\"");

    // Deeper down and at the top: the path names the object holding the key.
    std::string by = good;
    by.replace(by.find("\"by\": \"alice\""), 13, "\"by\": \"alice\", \"by\": \"mallory\"");
    auto signer = Registry::parse(by, "reg.json");
    ASSERT_FALSE(signer);
    EXPECT_EQ(signer.error().message, "reg.json: plugins[0].review: duplicate field \"by\"");
    auto format = Registry::parse(
        R"({"format": "acetate-registry/1", "plugins": [], "format": "acetate-registry/1"})",
        "reg.json");
    ASSERT_FALSE(format);
    EXPECT_EQ(format.error().message, "reg.json: duplicate field \"format\"");

    // Registry::load reads through the same parser.
    std::ofstream(dir_ / "twice.json") << twice;
    auto loaded = Registry::load(dir_ / "twice.json");
    ASSERT_FALSE(loaded);
    EXPECT_EQ(loaded.error().message,
              (dir_ / "twice.json").string() + ": plugins[0]: duplicate field \"binary_sha256\"");
}

TEST_F(RegistryFiles, FifoIsRefusedWithoutBlocking) {
    const fs::path fifo = dir_ / "registry.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    const BoundedLoad run = load_in_bounded_child(fifo);
    ASSERT_TRUE(run.finished) << run.ending;
    EXPECT_FALSE(run.loaded);
    EXPECT_EQ(run.message, fifo.string() + ": not a regular file (a FIFO)");
    EXPECT_LT(run.seconds, 5.0);
}

TEST_F(RegistryFiles, DevicesAndDirectoriesAreRefusedUnread) {
    const BoundedLoad zero = load_in_bounded_child("/dev/zero");
    ASSERT_TRUE(zero.finished) << zero.ending;
    EXPECT_FALSE(zero.loaded);
    EXPECT_EQ(zero.message, "/dev/zero: not a regular file (a character device)");
    EXPECT_LT(zero.seconds, 5.0);

    auto folder = Registry::load(dir_);
    ASSERT_FALSE(folder);
    EXPECT_EQ(folder.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(folder.error().message, dir_.string() + ": not a regular file (a directory)");
}

TEST_F(RegistryFiles, FileOverTheLimitIsRefusedUnread) {
    // Sparse: one byte over the limit takes no disk and, refused by its size, no time.
    const fs::path file = dir_ / "registry.json";
    std::ofstream(file).close();
    ASSERT_EQ(::truncate(file.c_str(), off_t(kMaxRegistryFileBytes + 1)), 0);
    static_assert(kMaxRegistryFileBytes == 64 << 20, "the message below states the limit");
    const auto start = std::chrono::steady_clock::now();
    auto loaded = Registry::load(file);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_FALSE(loaded);
    EXPECT_EQ(loaded.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(
        loaded.error().message,
        file.string() + ": 64.0 MiB (67108865 bytes) is over the 64 MiB limit for a registry");
    EXPECT_LT(seconds, 0.5) << "refused by its size, before reading";
}

}  // namespace
}  // namespace acetate
