#pragma once
// Small POSIX helpers shared by the one file reader (input_file.hpp) and the one file writer
// (atomic_file.hpp).

#include <fmt/format.h>
#include <sys/types.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <string_view>

#include "core/result.hpp"

namespace acetate {

// Owns a file descriptor: closed on every path out of a scope. close() is there for the success
// path, which must check what close() says (a deferred write error on a full or remote disk).
class FileDescriptor {
  public:
    explicit FileDescriptor(int fd) : fd_(fd) {}
    ~FileDescriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    int get() const { return fd_; }
    // Hands the descriptor to the caller, who closes it.
    int release() {
        const int fd = fd_;
        fd_ = -1;
        return fd;
    }
    int close() {
        const int result = ::close(fd_);
        fd_ = -1;
        return result;
    }

  private:
    int fd_;
};

// The one-line I/O error every file reader and writer gives: `<file>: <what failed>: <strerror>`.
inline Error io_error(const std::filesystem::path& file, std::string_view what, int err) {
    return make_error(ErrorCode::Io,
                      fmt::format("{}: {}: {}", file.string(), what, std::strerror(err)));
}

// What a file that is not a regular one is, for a one-line refusal: "a FIFO", "a directory"...
const char* file_kind(mode_t mode);

}  // namespace acetate
