#pragma once
// Named temporaries that a SIGINT or SIGTERM removes. A writer that must give its data a name
// before the final rename (write_file_atomically's fallback where the file system has no
// O_TMPFILE, and the instant between linking and renaming otherwise) guards that name, so a
// user pressing Ctrl-C, or a CI runner stopping the job, leaves no `<stem>.tmp-<pid>-<n><ext>`
// behind. (SIGKILL cannot be caught: the next write of the same target removes those.)
//
// The handler unlinks every guarded name, then lets the signal do what it did before: it
// restores the previous disposition and raises the signal again, or calls the previous handler
// when the program had installed its own. Each new guard puts it back in front if the program
// replaced it meanwhile.

#include <filesystem>

namespace acetate {

class TemporaryGuard {
  public:
    // Guards `file` until destruction. At most 64 names are guarded at once and a name longer
    // than 4095 bytes is not guarded; such a file is then only removed by the writer itself.
    explicit TemporaryGuard(const std::filesystem::path& file);
    ~TemporaryGuard();
    TemporaryGuard(const TemporaryGuard&) = delete;
    TemporaryGuard& operator=(const TemporaryGuard&) = delete;

    bool guarded() const { return slot_ >= 0; }

  private:
    int slot_ = -1;
};

}  // namespace acetate
