#include "plugins/sealed_library.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <openssl/evp.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <memory>

#include "core/file_descriptor.hpp"
#include "core/input_file.hpp"

namespace acetate {
namespace {

Error refusal(const std::string& where, std::string_view what) {
    return make_error(ErrorCode::InvalidInput, fmt::format("{}: {}", where, what));
}

Error system_error(const std::string& where, std::string_view what, int err) {
    return make_error(ErrorCode::Io, fmt::format("{}: {}: {}", where, what, std::strerror(err)));
}

// A memory file that may be sealed and mapped executable. Kernels from 6.3 on can be set to
// refuse executable memory files unless MFD_EXEC asks for one; older kernels do not know the
// flag (EINVAL) and allow it anyway.
int executable_memory_file(const char* name) {
#ifndef MFD_EXEC
    constexpr unsigned kMfdExec = 0x0010U;
#else
    constexpr unsigned kMfdExec = MFD_EXEC;
#endif
    const int fd = ::memfd_create(name, MFD_CLOEXEC | MFD_ALLOW_SEALING | kMfdExec);
    if (fd >= 0 || errno != EINVAL) return fd;
    return ::memfd_create(name, MFD_CLOEXEC | MFD_ALLOW_SEALING);
}

bool write_all(int fd, const char* data, size_t size) {
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        data += n;
        size -= size_t(n);
    }
    return true;
}

}  // namespace

Result<SealedLibrary> seal_library(const std::filesystem::path& file, const std::string& where) {
    FileDescriptor source(::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (source.get() < 0 && errno == ENOENT)
        return make_error(ErrorCode::FileNotFound, fmt::format("{}: file not found", where));
    if (source.get() < 0) return system_error(where, "cannot open", errno);
    struct stat st {};
    if (::fstat(source.get(), &st) != 0) return system_error(where, "cannot stat", errno);
    if (!S_ISREG(st.st_mode)) return refusal(where, "not a regular file, so not a plugin");
    if (std::uint64_t(st.st_size) > kMaxPluginFileBytes)
        return refusal(where, fmt::format("{} is over the {} limit for a plugin",
                                          describe_byte_count(std::uint64_t(st.st_size)),
                                          describe_byte_count(kMaxPluginFileBytes)));

    FileDescriptor sealed(executable_memory_file("acetate-plugin"));
    if (sealed.get() < 0) return system_error(where, "cannot create a sealed copy", errno);
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> hash(EVP_MD_CTX_new(), EVP_MD_CTX_free);
    if (!hash || EVP_DigestInit_ex(hash.get(), EVP_sha256(), nullptr) != 1)
        return refusal(where, "cannot start a SHA-256 digest");
    // Read to the end of what is there, not to st_size: a file that grows while copied is
    // caught by the limit; one that shrinks is copied as it ends. Either way, what is hashed
    // below is exactly what the copy holds.
    std::array<char, 1 << 16> buffer;
    std::uint64_t copied = 0;
    char magic[4] = {};
    for (;;) {
        const ssize_t n = ::read(source.get(), buffer.data(), buffer.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return system_error(where, "cannot read", errno);
        if (n == 0) break;
        if (copied < sizeof(magic))
            std::memcpy(magic + copied, buffer.data(),
                        std::min(sizeof(magic) - size_t(copied), size_t(n)));
        copied += std::uint64_t(n);
        if (copied > kMaxPluginFileBytes)
            return refusal(where, fmt::format("grew past the {} limit for a plugin while read",
                                              describe_byte_count(kMaxPluginFileBytes)));
        if (!write_all(sealed.get(), buffer.data(), size_t(n)))
            return system_error(where, "cannot copy into a sealed memory file", errno);
        EVP_DigestUpdate(hash.get(), buffer.data(), size_t(n));
    }
    static constexpr char kElfMagic[4] = {0x7f, 'E', 'L', 'F'};
    if (copied < sizeof(magic) || std::memcmp(magic, kElfMagic, sizeof(magic)) != 0)
        return refusal(where, "not a shared library (it does not start with an ELF header)");
    constexpr int kSeals = F_SEAL_WRITE | F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_SEAL;
    if (::fcntl(sealed.get(), F_ADD_SEALS, kSeals) != 0)
        return system_error(where, "cannot seal the copy", errno);

    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    EVP_DigestFinal_ex(hash.get(), digest, &length);
    SealedLibrary out;
    for (unsigned i = 0; i < length; ++i) out.sha256 += fmt::format("{:02x}", digest[i]);
    // Ownership passes to the caller: the descriptor must outlive the mapping's name.
    out.fd = sealed.release();
    out.path = fmt::format("/proc/self/fd/{}", out.fd);
    return out;
}

}  // namespace acetate
