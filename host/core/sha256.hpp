#pragma once
// SHA-256 through OpenSSL's libcrypto, as lowercase hex.

#include <cstddef>
#include <string>
#include <string_view>

namespace acetate {

std::string sha256_hex(const void* data, size_t size);
inline std::string sha256_hex(std::string_view text) {
    return sha256_hex(text.data(), text.size());
}

}  // namespace acetate
