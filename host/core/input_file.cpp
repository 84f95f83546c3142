#include "core/input_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>

#include "core/file_descriptor.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

Error not_regular(const fs::path& file, mode_t mode) {
    return make_error(ErrorCode::InvalidInput,
                      fmt::format("{}: not a regular file ({})", file.string(), file_kind(mode)));
}

// nullopt when the file does not exist; every other failure is an Error.
Result<std::optional<std::string>> read_checked(const fs::path& file, std::uint64_t max_bytes,
                                                std::string_view what) {
    // O_NONBLOCK: opening a FIFO for reading waits for a writer without it. O_NOCTTY: a
    // terminal named as input must not become this process's controlling terminal.
    FileDescriptor fd(::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (fd.get() < 0) {
        const int err = errno;
        if (err == ENOENT) return std::optional<std::string>();
        // A socket cannot be opened at all (ENXIO): say what it is rather than "no such
        // device or address".
        struct stat st {};
        if (err == ENXIO && ::stat(file.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
            return not_regular(file, st.st_mode);
        return io_error(file, "cannot open", err);
    }
    // The descriptor's own type and size: nothing can swap the file between check and read.
    struct stat st {};
    if (::fstat(fd.get(), &st) != 0) return io_error(file, "cannot stat", errno);
    if (!S_ISREG(st.st_mode)) return not_regular(file, st.st_mode);
    const std::string limit =
        fmt::format("the {} limit for {}", describe_byte_count(max_bytes), what);
    if (st.st_size > 0 && std::uint64_t(st.st_size) > max_bytes)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: {} is over {}", file.string(),
                                      describe_byte_count(std::uint64_t(st.st_size)), limit));

    std::string bytes;
    bytes.reserve(size_t(st.st_size));
    std::array<char, 1 << 16> buffer;
    for (;;) {
        const ssize_t n = ::read(fd.get(), buffer.data(), buffer.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return io_error(file, "cannot read", errno);
        if (n == 0) break;
        // The file may grow after fstat (or report no size at all, as /proc files do).
        if (bytes.size() + size_t(n) > max_bytes)
            return make_error(
                ErrorCode::InvalidInput,
                fmt::format("{}: grew past {} while being read", file.string(), limit));
        bytes.append(buffer.data(), size_t(n));
    }
    return std::optional<std::string>(std::move(bytes));
}

}  // namespace

Result<std::string> read_input_file(const fs::path& file, std::uint64_t max_bytes,
                                    std::string_view what) {
    auto bytes = read_checked(file, max_bytes, what);
    if (!bytes) return bytes.error();
    if (!bytes.value())
        return make_error(ErrorCode::FileNotFound,
                          fmt::format("{}: file not found", file.string()));
    return std::move(*bytes.value());
}

Result<std::optional<std::string>> read_input_file_if_exists(const fs::path& file,
                                                             std::uint64_t max_bytes,
                                                             std::string_view what) {
    return read_checked(file, max_bytes, what);
}

std::string describe_byte_count(std::uint64_t bytes) {
    if (bytes < 1024) return fmt::format("{} byte{}", bytes, bytes == 1 ? "" : "s");
    constexpr std::array<const char*, 6> kUnits = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    size_t unit = 0;
    std::uint64_t scale = 1024;
    while (unit + 1 < kUnits.size() && bytes / scale >= 1024) {
        scale *= 1024;
        ++unit;
    }
    if (bytes % scale == 0) return fmt::format("{} {}", bytes / scale, kUnits[unit]);
    return fmt::format("{:.1f} {} ({} bytes)", double(bytes) / double(scale), kUnits[unit], bytes);
}

const char* file_kind(mode_t mode) {
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a kind of file the host reads";
}

}  // namespace acetate
