#include "registry_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>
#include <regex>

#include "core/number_text.hpp"

namespace acetate::registry_fields {

namespace fs = std::filesystem;

bool is_hex64(std::string_view s) {
    return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
           });
}

std::optional<std::array<uint32_t, 3>> parse_version(std::string_view s) {
    std::array<uint32_t, 3> out{};
    for (size_t i = 0; i < 3; ++i) {
        const size_t dot = i < 2 ? s.find('.') : s.size();
        if (dot == std::string_view::npos || dot == 0) return std::nullopt;
        const std::string_view part = s.substr(0, dot);
        auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), out[i]);
        if (ec != std::errc() || end != part.data() + part.size()) return std::nullopt;
        s.remove_prefix(std::min(s.size(), dot + 1));
        if (i < 2 && s.empty()) return std::nullopt;
    }
    return out;
}

// The day of either goes through the one reader of days (core/number_text.hpp), so a day that
// does not exist (2026-02-30, 2100-02-29) is refused here as it is on the command line.
bool is_timestamp(const std::string& s) {
    static const std::regex pattern("\\d{4}-\\d{2}-\\d{2}T([01]\\d|2[0-3]):[0-5]\\d:[0-5]\\dZ");
    return std::regex_match(s, pattern) && number_text::day(s.substr(0, 10), "").ok();
}

bool is_day(const std::string& s) {
    return number_text::day(s, "").ok();
}

bool is_blank(std::string_view s) {
    return std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isspace(c); });
}

std::string short_hash(std::string_view hash) {
    return std::string(hash.substr(0, 12));
}

std::string plugin_name(std::string_view id, std::string_view version) {
    return fmt::format("{} {}", id, version);
}

Error refused(std::string_view id, std::string_view version, const std::string& what) {
    return make_error(ErrorCode::InvalidInput,
                      fmt::format("{}: {}", plugin_name(id, version), what));
}

Error io_error(const fs::path& file, std::string_view what, int err) {
    return make_error(ErrorCode::Io,
                      fmt::format("{}: {}: {}", file.string(), what, std::strerror(err)));
}

ValidationStage next(ValidationStage s) {
    return ValidationStage(int(s) + 1);
}

bool entry_less(const RegistryEntry& a, const RegistryEntry& b) {
    if (a.id != b.id) return a.id < b.id;
    return parse_version(a.version) < parse_version(b.version);
}

}  // namespace acetate::registry_fields
