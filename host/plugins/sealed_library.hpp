#pragma once
// The bytes checked are the bytes run: a plugin file is copied once into a sealed memory file
// (memfd_create, then F_SEAL_WRITE | F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_SEAL), hashed there,
// judged by the load policy there, and dlopened from there. Holding the original file open is
// not enough: dlopen of /proc/self/fd/N maps the same inode, so a file rewritten in place
// between the check and the mapping would run bytes nobody checked. A sealed copy can change
// for nobody, this process included.

#include <cstdint>
#include <filesystem>
#include <string>

#include "core/result.hpp"

namespace acetate {

// The largest plugin file loaded. Shipped plugins are a few hundred KiB with their shaders
// embedded; 256 MiB leaves room for large baked tables while keeping a copy in memory cheap.
inline constexpr std::uint64_t kMaxPluginFileBytes = std::uint64_t(256) << 20;

struct SealedLibrary {
    int fd = -1;                 // the sealed memory file; owned by the caller
    std::filesystem::path path;  // /proc/self/fd/<fd>: what the policy reads and dlopen maps
    std::string sha256;          // lowercase hex of the sealed bytes
};

// Copies `file` (a regular file, at most kMaxPluginFileBytes, starting with an ELF header) into
// a sealed memory file. Errors are one line starting with `where` (the file as the user named
// it): "file not found", "not a regular file, so not a plugin", "not a shared library (...)",
// the size limit, or the system's reason.
Result<SealedLibrary> seal_library(const std::filesystem::path& file, const std::string& where);

}  // namespace acetate
