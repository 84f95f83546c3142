#include "json_fields.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace acetate::json_fields {

namespace {

// Keys and values come from the file being read and may hold any character; an error stays one
// line by writing control characters as escapes ("\n", "\x01").
std::string one_line(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n')
            out += "\\n";
        else if (c == '\r')
            out += "\\r";
        else if (c == '\t')
            out += "\\t";
        else if (u < 0x20 || u == 0x7f)
            out += fmt::format("\\x{:02x}", u);
        else
            out += c;
    }
    return out;
}

}  // namespace

void fail(const std::string& path, std::string what) {
    throw JsonFieldError{one_line(path), one_line(what)};
}

std::string field(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}

std::string element(const std::string& path, size_t index) {
    return fmt::format("{}[{}]", path, index);
}

void expect_object(const nlohmann::json& j, const std::string& path,
                   const std::vector<std::string_view>& required,
                   const std::vector<std::string_view>& optional) {
    if (!j.is_object()) fail(path, fmt::format("must be an object, found {}", j.type_name()));
    auto known = [&](const std::string& key) {
        auto in = [&](const std::vector<std::string_view>& keys) {
            return std::find(keys.begin(), keys.end(), key) != keys.end();
        };
        return in(required) || in(optional);
    };
    for (const auto& item : j.items())
        if (!known(item.key())) {
            std::vector<std::string_view> all = required;
            all.insert(all.end(), optional.begin(), optional.end());
            fail(field(path, item.key()),
                 fmt::format("unknown field (this format has: {})", fmt::join(all, ", ")));
        }
    for (std::string_view key : required)
        if (!j.contains(key)) fail(field(path, key), "missing");
}

}  // namespace acetate::json_fields
