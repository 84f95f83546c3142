#include "core/sha256.hpp"

#include <openssl/evp.h>

#include <limits>

#include "core/check.hpp"
#include "core/input_file.hpp"

namespace acetate {

Sha256Digest sha256_digest(const void* data, size_t size) {
    Sha256Digest digest{};
    unsigned int length = 0;
    // EVP_Digest fails only when libcrypto itself is broken (no SHA-256 provider): nothing a
    // caller could handle.
    const int ok = EVP_Digest(data, size, digest.data(), &length, EVP_sha256(), nullptr);
    ACETATE_CHECK(ok == 1 && length == digest.size(), "libcrypto's SHA-256 failed");
    return digest;
}

std::string sha256_hex(const void* data, size_t size) {
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (uint8_t byte : sha256_digest(data, size)) {
        out += hex[byte >> 4];
        out += hex[byte & 15];
    }
    return out;
}

Result<std::string> file_sha256(const std::filesystem::path& file) {
    auto bytes = read_input_file(file, std::numeric_limits<std::uint64_t>::max(), "a plugin");
    if (!bytes) return bytes.error();
    return sha256_hex(bytes.value());
}

}  // namespace acetate
