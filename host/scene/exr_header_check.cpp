#include "scene/exr_header_check.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <string>

namespace acetate {
namespace {

constexpr unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};
constexpr uint32_t kMultipartFlag = 0x1000;  // version field: several headers follow
constexpr size_t kMaxName = 255;             // OpenEXR's longest attribute or type name

uint32_t little_endian_u32(const char* p) {
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | uint8_t(p[i]);
    return v;
}

// A name from the file as it can appear in a one-line message: bytes outside printable ASCII
// (a newline in a damaged file) are written as \xNN.
std::string printable(const std::string& name) {
    std::string out;
    for (unsigned char c : name)
        out += c >= 0x20 && c < 0x7f && c != '"' ? std::string(1, char(c))
                                                 : fmt::format("\\x{:02x}", c);
    return out;
}

}  // namespace

Result<void> check_exr_header(std::string_view bytes, const std::filesystem::path& file,
                              int max_side) {
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, 4) != 0) return {};
    auto bad = [&](const std::string& what) {
        return make_error(ErrorCode::ImageDecode,
                          fmt::format("{}: EXR header: {}", file.string(), what));
    };
    const bool multipart = (little_endian_u32(bytes.data() + 4) & kMultipartFlag) != 0;
    size_t at = 8;
    // A zero-terminated name at `at`, at most kMaxName bytes.
    auto name_at = [&](std::string& out) {
        const size_t end = bytes.find('\0', at);
        if (end == std::string_view::npos || end - at > kMaxName) return false;
        out.assign(bytes.substr(at, end - at));
        at = end + 1;
        return true;
    };
    for (int header = 0;; ++header) {
        std::string name, type;
        int attributes = 0;
        for (;; ++attributes) {
            if (!name_at(name)) return bad("an attribute name runs past the file or 255 bytes");
            if (name.empty()) break;  // the end of this header
            if (!name_at(type))
                return bad(
                    fmt::format("attribute \"{}\": its type name runs "
                                "past the file or 255 bytes",
                                printable(name)));
            if (bytes.size() - at < 4)
                return bad(
                    fmt::format("attribute \"{}\": the file ends in its size", printable(name)));
            const uint32_t size = little_endian_u32(bytes.data() + at);
            at += 4;
            if (size > bytes.size() - at)
                return bad(fmt::format("attribute \"{}\" declares {} bytes; the file has {} left",
                                       printable(name), size, bytes.size() - at));
            if (name == "dataWindow" && type == "box2i" && size == 16) {
                const auto coordinate = [&](size_t i) {
                    return int64_t(int32_t(little_endian_u32(bytes.data() + at + 4 * i)));
                };
                const int64_t width = coordinate(2) - coordinate(0) + 1;
                const int64_t height = coordinate(3) - coordinate(1) + 1;
                if (width > max_side || height > max_side)
                    return bad(fmt::format("data window {}x{} is larger than {} on a side", width,
                                           height, max_side));
            }
            at += size;
        }
        // A single-part file has one header; a multipart one ends with an empty header.
        if (!multipart || attributes == 0) break;
    }
    return {};
}

}  // namespace acetate
