#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <regex>

#include "core/file_descriptor.hpp"
#include "core/temporary_guard.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

fs::path folder_of(const fs::path& file) {
    return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

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

// Writes, flushes to disk and closes: the three places a full or failing disk reports.
Result<void> write_sync_close(FileDescriptor& fd, std::string_view bytes, const fs::path& file) {
    ACETATE_TRY(write_all(fd.get(), bytes, file));
    if (::fsync(fd.get()) != 0) return io_error(file, "flushing to disk failed", errno);
    return {};
}

// After the rename the folder entry must reach the disk too, or a crash can lose the new name.
// Best effort: some file systems refuse fsync on a folder, and the data is safe anyway.
void sync_folder_of(const fs::path& file) {
    FileDescriptor fd(::open(folder_of(file).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (fd.get() >= 0) (void)::fsync(fd.get());
}

Result<void> rename_over(const fs::path& temp, const fs::path& file) {
    if (::rename(temp.c_str(), file.c_str()) != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        return io_error(file, "cannot replace it", err);
    }
    sync_folder_of(file);
    return {};
}

// Refuses to replace what is not a regular file: renaming over /dev/null as root would
// replace the device node, and over a folder cannot work.
Result<void> check_target(const fs::path& file) {
    struct stat st {};
    if (::lstat(file.c_str(), &st) != 0) {
        if (errno == ENOENT) return {};
        return io_error(file, "cannot inspect it", errno);
    }
    if (S_ISREG(st.st_mode) || S_ISLNK(st.st_mode)) return {};
    return make_error(ErrorCode::Io, fmt::format("{}: will not replace it: it is {}", file.string(),
                                                 file_kind(st.st_mode)));
}

// The unnamed-temporary path; returns false (and nothing done) where O_TMPFILE is unsupported.
Result<bool> write_through_unnamed_temp(const fs::path& file, std::string_view bytes) {
    FileDescriptor fd(::open(folder_of(file).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644));
    if (fd.get() < 0) {
        if (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL) return false;
        return io_error(file, fmt::format("cannot create a file in {}", folder_of(file).string()),
                        errno);
    }
    ACETATE_TRY(write_sync_close(fd, bytes, file));
    // The data is on disk; give it a name only now, for the instant before the rename.
    const fs::path temp = temp_sibling(file);
    const TemporaryGuard guard(temp);  // a SIGINT/SIGTERM before the rename removes the name
    const std::string self = fmt::format("/proc/self/fd/{}", fd.get());
    if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, temp.c_str(), AT_SYMLINK_FOLLOW) != 0) {
        const int err = errno;
        if (err == ENOENT) return false;  // no /proc: the named path still works
        return io_error(file, "cannot link the written data into its folder", err);
    }
    if (fd.close() != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        return io_error(file, "closing failed", err);
    }
    ACETATE_TRY(rename_over(temp, file));
    return true;
}

Result<void> write_through_named_temp(const fs::path& file, std::string_view bytes) {
    remove_dead_writers_temporaries(file);
    const fs::path temp = temp_sibling(file);
    const TemporaryGuard guard(temp);  // a SIGINT/SIGTERM while it exists removes it
    FileDescriptor fd(::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644));
    if (fd.get() < 0)
        return io_error(file, fmt::format("cannot create a file in {}", folder_of(file).string()),
                        errno);
    auto written = write_sync_close(fd, bytes, file);
    if (written && fd.close() != 0) written = io_error(file, "closing failed", errno);
    if (!written) {
        ::unlink(temp.c_str());
        return written;
    }
    return rename_over(temp, file);
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

void remove_dead_writers_temporaries(const fs::path& file) {
    static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
    const std::regex pattern(std::regex_replace(file.stem().string(), special, R"(\$&)") +
                             R"(\.tmp-(\d+)-\d+)" +
                             std::regex_replace(file.extension().string(), special, R"(\$&)"));
    std::error_code ec;
    for (const auto& item : fs::directory_iterator(folder_of(file), ec)) {
        std::smatch match;
        const std::string name = item.path().filename().string();
        if (!std::regex_match(name, match, pattern) || !item.is_regular_file(ec)) continue;
        const long pid = std::strtol(match[1].str().c_str(), nullptr, 10);
        if (pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) fs::remove(item.path(), ec);
    }
}

Result<void> write_file_atomically(const fs::path& file, std::string_view bytes) {
    ACETATE_TRY(check_target(file));
    auto unnamed = write_through_unnamed_temp(file, bytes);
    if (!unnamed) return unnamed.error();
    if (unnamed.value()) return {};
    return write_through_named_temp(file, bytes);
}

}  // namespace acetate
