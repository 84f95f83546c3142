#include "core/fork_server.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>

extern char** environ;

namespace acetate {
namespace {

// A request is a count, then each string as its length and bytes (uint32 in the machine's
// order: both ends are this program). The first string is the log, the rest the arguments.
constexpr uint32_t kMaxStrings = 4096;
constexpr uint32_t kMaxStringBytes = 1 << 20;
// How long the caller waits for the server to answer a request: a fork takes milliseconds.
constexpr int kReplyMilliseconds = 10000;

bool send_all(int fd, const void* data, size_t size) {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::send(fd, p, size, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        size -= size_t(n);
    }
    return true;
}

// Reads exactly `size` bytes; false on end of file or error.
bool read_all(int fd, void* data, size_t size) {
    char* p = static_cast<char*>(data);
    while (size > 0) {
        const ssize_t n = ::read(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        size -= size_t(n);
    }
    return true;
}

bool read_request(int fd, std::vector<std::string>& strings) {
    uint32_t count = 0;
    if (!read_all(fd, &count, sizeof count) || count < 2 || count > kMaxStrings) return false;
    strings.assign(count, {});
    for (std::string& s : strings) {
        uint32_t size = 0;
        if (!read_all(fd, &size, sizeof size) || size > kMaxStringBytes) return false;
        s.resize(size);
        if (size > 0 && !read_all(fd, s.data(), size)) return false;
    }
    return true;
}

// exit() in a forked child would run the server's exit handlers, which join the server's
// threads; they do not exist here, so it would hang. Registered last, this runs first.
void exit_at_once(int status, void*) {
    std::fflush(nullptr);
    ::_exit(status);
}

// In the grandchild: the descriptors, signals and exit of a freshly exec'd child, then `run`.
[[noreturn]] void become_child(const std::vector<std::string>& request,
                               const std::function<int(int, char**)>& run, pid_t middle) {
    // Run only once reparented to the subreaper: a program that ties itself to its parent
    // (PR_SET_PDEATHSIG, as acetate-harness's children do) must tie itself to the caller, not
    // to the middle process, which exits at once and would take the child with it. (The
    // middle's pid is passed in: it may be gone before this line runs.)
    while (::getppid() == middle) ::usleep(100);
    const int log = ::open(request[0].c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    const int null = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (log < 0 || null < 0) ::_exit(127);
    ::dup2(null, STDIN_FILENO);
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    ::close_range(3, ~0u, 0);
    ::signal(SIGPIPE, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::on_exit(exit_at_once, nullptr);
    std::vector<char*> argv;
    for (size_t i = 1; i < request.size(); ++i)
        argv.push_back(const_cast<char*>(request[i].c_str()));
    argv.push_back(nullptr);
    const int code = run(int(argv.size() - 1), argv.data());
    std::cout.flush();
    std::cerr.flush();
    exit_at_once(code, nullptr);
    ::_exit(code);  // not reached
}

// Forks the grandchild through a middle process that exits at once, so the grandchild is
// reparented to the subreaper that started the server; its pid, or -errno.
int32_t fork_orphan(const std::vector<std::string>& request,
                    const std::function<int(int, char**)>& run) {
    int link[2];
    if (::pipe2(link, O_CLOEXEC) != 0) return -errno;
    const pid_t middle = ::fork();
    if (middle < 0) {
        const int error = errno;
        ::close(link[0]);
        ::close(link[1]);
        return -error;
    }
    if (middle == 0) {
        ::close(link[0]);
        const pid_t self = ::getpid();
        const pid_t child = ::fork();
        if (child == 0) become_child(request, run, self);
        const int32_t answer = child < 0 ? -errno : int32_t(child);
        (void)!::write(link[1], &answer, sizeof answer);
        ::_exit(0);
    }
    ::close(link[1]);
    int32_t answer = -EPIPE;
    if (!read_all(link[0], &answer, sizeof answer)) answer = -EPIPE;
    ::close(link[0]);
    // Once the middle process is gone, the grandchild belongs to the subreaper: only then is
    // its pid handed back, so the caller can wait for it at once.
    while (::waitpid(middle, nullptr, 0) < 0 && errno == EINTR) {
    }
    return answer;
}

// The threads of this process now.
size_t thread_count() {
    std::error_code ec;
    size_t count = 0;
    for (auto it = std::filesystem::directory_iterator("/proc/self/task", ec);
         !ec && it != std::filesystem::directory_iterator(); it.increment(ec))
        ++count;
    return count;
}

}  // namespace

int serve_forks(const std::function<int(int argc, char** argv)>& run,
                const std::function<bool(std::string& error)>& prepare) {
    ::signal(SIGPIPE, SIG_IGN);
    if (prepare) {
        const size_t threads = thread_count();
        std::string error;
        const bool prepared = prepare(error);
        if (!prepared && error.empty()) error = "it failed";
        if (prepared && thread_count() > threads)
            error = "it started " + std::to_string(thread_count() - threads) + " thread(s)";
        if (!error.empty()) {
            std::fprintf(stderr,
                         "fork server: cannot prepare the children (%s); they are "
                         "started one by one instead\n",
                         error.c_str());
            return 1;
        }
    }
    std::vector<std::string> request;
    while (read_request(STDIN_FILENO, request)) {
        const int32_t answer = fork_orphan(request, run);
        if (!send_all(STDIN_FILENO, &answer, sizeof answer)) return 1;
    }
    return 0;
}

std::unique_ptr<ForkServer> ForkServer::start(const std::vector<std::string>& server_argv,
                                              std::string& error) {
    int pair[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair) != 0) {
        error = std::string("socketpair: ") + std::strerror(errno);
        return nullptr;
    }
    if (::prctl(PR_SET_CHILD_SUBREAPER, 1) != 0) {
        error = std::string("PR_SET_CHILD_SUBREAPER: ") + std::strerror(errno);
        ::close(pair[0]);
        ::close(pair[1]);
        return nullptr;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pair[1], STDIN_FILENO);
    std::vector<char*> argv;
    for (const std::string& arg : server_argv) argv.push_back(const_cast<char*>(arg.c_str()));
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int spawned = ::posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pair[1]);
    if (spawned != 0) {
        error = "cannot start " + server_argv[0] + ": " + std::strerror(spawned);
        ::close(pair[0]);
        return nullptr;
    }
    std::unique_ptr<ForkServer> server(new ForkServer());
    server->socket_ = pair[0];
    server->pid_ = pid;
    return server;
}

ForkServer::~ForkServer() {
    if (socket_ >= 0) ::close(socket_);
    if (pid_ > 0) {
        if (broken_) ::kill(pid_, SIGKILL);
        while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
        }
    }
}

pid_t ForkServer::launch(const std::vector<std::string>& argv, const std::string& log,
                         std::string& error) {
    if (broken_) {
        error = "the fork server stopped answering";
        return -1;
    }
    std::vector<std::string> strings{log};
    strings.insert(strings.end(), argv.begin(), argv.end());
    bool sent = true;
    const uint32_t count = uint32_t(strings.size());
    sent = send_all(socket_, &count, sizeof count);
    for (const std::string& s : strings) {
        const uint32_t size = uint32_t(s.size());
        sent = sent && send_all(socket_, &size, sizeof size) && send_all(socket_, s.data(), size);
    }
    int32_t answer = -EPIPE;
    pollfd ready{socket_, POLLIN, 0};
    const bool answered = sent && ::poll(&ready, 1, kReplyMilliseconds) == 1 &&
                          read_all(socket_, &answer, sizeof answer);
    if (!answered || answer <= 0) {
        broken_ = !answered;
        error = answered ? std::string("the fork server could not fork: ") + std::strerror(-answer)
                         : "the fork server stopped answering";
        return -1;
    }
    return pid_t(answer);
}

}  // namespace acetate
