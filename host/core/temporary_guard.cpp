#include "core/temporary_guard.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <mutex>

namespace acetate {
namespace {

constexpr int kSlots = 64;
constexpr size_t kPathBytes = 4096;
enum SlotState : int { kFree = 0, kFilling = 1, kReady = 2 };

// Read by the signal handler: lock-free atomics and plain bytes written before the release.
struct Slot {
    std::atomic<int> state{kFree};
    char path[kPathBytes];
};
Slot g_slots[kSlots];
struct sigaction g_previous[2];  // SIGINT, SIGTERM

int signal_index(int signal) {
    return signal == SIGINT ? 0 : 1;
}

void remove_guarded_and_forward(int signal, siginfo_t* info, void* context) {
    for (Slot& slot : g_slots)
        if (slot.state.load(std::memory_order_acquire) == kReady) ::unlink(slot.path);
    const struct sigaction& previous = g_previous[signal_index(signal)];
    if (previous.sa_flags & SA_SIGINFO) {
        if (previous.sa_sigaction) previous.sa_sigaction(signal, info, context);
        return;
    }
    if (previous.sa_handler != SIG_DFL && previous.sa_handler != SIG_IGN) {
        previous.sa_handler(signal);
        return;
    }
    // What the signal did before: restore it and deliver again (SIG_DFL ends the process with
    // the signal, so the parent sees how it ended).
    ::sigaction(signal, &previous, nullptr);
    if (previous.sa_handler == SIG_DFL) ::raise(signal);
}

// Puts the handler in front of whatever handles SIGINT and SIGTERM now. Checked at every guard,
// not once: a program that installs its own handler after an earlier write gets it chained
// rather than losing the cleanup.
void install_in_front() {
    static std::mutex mutex;
    const std::lock_guard lock(mutex);
    for (int signal : {SIGINT, SIGTERM}) {
        struct sigaction current {};
        ::sigaction(signal, nullptr, &current);
        if ((current.sa_flags & SA_SIGINFO) && current.sa_sigaction == remove_guarded_and_forward)
            continue;
        // A signal the program ignores stays ignored: nothing ends, nothing to clean.
        if (!(current.sa_flags & SA_SIGINFO) && current.sa_handler == SIG_IGN) continue;
        g_previous[signal_index(signal)] = current;
        struct sigaction action {};
        action.sa_sigaction = remove_guarded_and_forward;
        action.sa_flags = SA_SIGINFO | SA_RESTART;
        sigemptyset(&action.sa_mask);
        ::sigaction(signal, &action, nullptr);
    }
}

}  // namespace

TemporaryGuard::TemporaryGuard(const std::filesystem::path& file) {
    const std::string& path = file.native();
    if (path.size() >= kPathBytes) return;
    install_in_front();
    for (int i = 0; i < kSlots; ++i) {
        int expected = kFree;
        if (!g_slots[i].state.compare_exchange_strong(expected, kFilling,
                                                      std::memory_order_acquire))
            continue;
        std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
        g_slots[i].state.store(kReady, std::memory_order_release);
        slot_ = i;
        return;
    }
}

TemporaryGuard::~TemporaryGuard() {
    if (slot_ >= 0) g_slots[slot_].state.store(kFree, std::memory_order_release);
}

}  // namespace acetate
