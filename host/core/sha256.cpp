#include "core/sha256.hpp"

#include <openssl/evp.h>

#include <cassert>

namespace acetate {

std::string sha256_hex(const void* data, size_t size) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    const int ok = EVP_Digest(data, size, digest, &length, EVP_sha256(), nullptr);
    assert(ok == 1 && length == 32);
    (void)ok;
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < length; ++i) {
        out += hex[digest[i] >> 4];
        out += hex[digest[i] & 15];
    }
    return out;
}

}  // namespace acetate
