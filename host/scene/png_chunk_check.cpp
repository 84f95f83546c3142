#include "scene/png_chunk_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

namespace acetate {
namespace {

constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

uint32_t big_endian_u32(const char* p) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | uint8_t(p[i]);
    return v;
}

// A chunk's type for a one-line message: PNG types are four ASCII letters, quoted; a damaged
// one is written as its four bytes in hex.
std::string chunk_name(std::string_view type) {
    const bool letters = std::all_of(type.begin(), type.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    });
    if (letters) return "'" + std::string(type) + "'";
    return fmt::format("0x{:02x}{:02x}{:02x}{:02x}", uint8_t(type[0]), uint8_t(type[1]),
                       uint8_t(type[2]), uint8_t(type[3]));
}

}  // namespace

Result<void> check_png_chunks(std::string_view bytes, const std::filesystem::path& file) {
    if (bytes.size() < sizeof kSignature || std::memcmp(bytes.data(), kSignature, 8) != 0)
        return {};
    // Each chunk: a 4-byte length, a 4-byte type, the data, a 4-byte CRC. Up to IEND, every
    // chunk must fit in the file; what follows IEND is not read by libpng.
    size_t at = sizeof kSignature;
    while (at + 8 <= bytes.size()) {
        const uint32_t length = big_endian_u32(bytes.data() + at);
        const std::string_view type = bytes.substr(at + 4, 4);
        const size_t left = bytes.size() - at - 8;
        if (uint64_t(length) + 4 > left)
            return make_error(ErrorCode::ImageDecode,
                              fmt::format("{}: PNG chunk {} at byte {} declares {} bytes of "
                                          "data, but the file has {} left after its header",
                                          file.string(), chunk_name(type), at, length, left));
        if (type == "IEND") return {};
        at += 12 + size_t(length);
    }
    return {};  // no IEND: libpng says so in its own words
}

}  // namespace acetate
