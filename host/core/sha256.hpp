#pragma once
// SHA-256 through OpenSSL's libcrypto: the project's one digest helper (pipeline-pool keys,
// the pipeline cache's integrity hash, plugin binaries for the registry, reference scenes).

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace acetate {

using Sha256Digest = std::array<uint8_t, 32>;

Sha256Digest sha256_digest(const void* data, size_t size);
// Lowercase hex.
std::string sha256_hex(const void* data, size_t size);
inline std::string sha256_hex(std::string_view text) {
    return sha256_hex(text.data(), text.size());
}
// Lowercase hex SHA-256 of a file's bytes (a plugin binary: no size limit, opened without
// blocking, regular files only); an error naming the file on failure.
Result<std::string> file_sha256(const std::filesystem::path& file);

}  // namespace acetate
