#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace acetate {
namespace {

namespace fs = std::filesystem;

Error io_error(const fs::path& file, std::string_view what, int err) {
    return make_error(ErrorCode::Io,
                      fmt::format("{}: {}: {}", file.string(), what, std::strerror(err)));
}

// Closes on every path out of the functions below.
class FileDescriptor {
  public:
    explicit FileDescriptor(int fd) : fd_(fd) {}
    ~FileDescriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    int get() const { return fd_; }
    // close() can report a deferred write error, so the success path checks it.
    int close() {
        const int result = ::close(fd_);
        fd_ = -1;
        return result;
    }

  private:
    int fd_;
};

Result<void> write_all(int fd, std::string_view bytes, const fs::path& file) {
    while (!bytes.empty()) {
        const ssize_t written = ::write(fd, bytes.data(), bytes.size());
        if (written < 0) {
            if (errno == EINTR) continue;
            return io_error(file, "write failed", errno);
        }
        bytes.remove_prefix(size_t(written));
    }
    return {};
}

Result<void> sync_path(const fs::path& path, const fs::path& named) {
    FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0) return io_error(named, "cannot open for fsync", errno);
    if (::fsync(fd.get()) != 0) return io_error(named, "fsync failed", errno);
    return {};
}

// After the rename the directory entry must reach the disk too, or a crash can lose the new
// name. Best effort: some file systems refuse fsync on a directory, and the data is safe anyway.
void sync_directory_of(const fs::path& file) {
    const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
    FileDescriptor fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (fd.get() >= 0) (void)::fsync(fd.get());
}

Result<void> write_temp(const fs::path& temp, std::string_view bytes, const fs::path& file) {
    FileDescriptor fd(::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
    if (fd.get() < 0) return io_error(file, "cannot create " + temp.string(), errno);
    ACETATE_TRY(write_all(fd.get(), bytes, file));
    if (::fsync(fd.get()) != 0) return io_error(file, "fsync failed", errno);
    if (fd.close() != 0) return io_error(file, "close failed", errno);
    return {};
}

// The temporary is already on disk; a failed rename must not leave it behind.
Result<void> rename_over(const fs::path& temp, const fs::path& file) {
    if (::rename(temp.c_str(), file.c_str()) != 0) {
        const int err = errno;
        std::error_code ignored;
        fs::remove(temp, ignored);
        return io_error(file, "cannot rename " + temp.string() + " over it", err);
    }
    sync_directory_of(file);
    return {};
}

}  // namespace

fs::path temp_sibling(const fs::path& file) {
    // The counter keeps two writers in one process (threads) from sharing a temporary.
    static std::atomic<unsigned> counter{0};
    const unsigned n = counter.fetch_add(1, std::memory_order_relaxed);
    const std::string name = fmt::format("{}.tmp-{}-{}{}", file.stem().string(), ::getpid(), n,
                                         file.extension().string());
    return file.has_parent_path() ? file.parent_path() / name : fs::path(name);
}

Result<void> replace_with_temp(const fs::path& temp, const fs::path& file) {
    if (auto synced = sync_path(temp, file); !synced) {
        std::error_code ignored;
        fs::remove(temp, ignored);
        return synced.error();
    }
    return rename_over(temp, file);
}

Result<void> write_file_atomically(const fs::path& file, std::string_view bytes) {
    const fs::path temp = temp_sibling(file);
    if (auto written = write_temp(temp, bytes, file); !written) {
        std::error_code ignored;
        fs::remove(temp, ignored);
        return written.error();
    }
    return rename_over(temp, file);
}

}  // namespace acetate
