#include "core/json_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace acetate::json_fields {

using nlohmann::json;
namespace {

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

std::string joined(const std::vector<std::string_view>& names) {
    std::string out;
    for (std::string_view name : names) out += (out.empty() ? "" : ", ") + std::string(name);
    return out;
}

}  // namespace

void fail(const std::string& path, std::string what, ErrorCode code) {
    throw JsonFieldError{one_line(path), one_line(what), code};
}

std::string field(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}

std::string element(const std::string& path, size_t index) {
    return fmt::format("{}[{}]", path, index);
}

std::string describe(const nlohmann::json& value) {
    if (value.is_structured()) return std::string(value.type_name());
    return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string json_quoted(std::string_view text) {
    return json(std::string(text)).dump(-1, ' ', false, json::error_handler_t::replace);
}

void expect_object(const nlohmann::json& j, const std::string& path,
                   const std::vector<std::string_view>& required,
                   const std::vector<std::string_view>& optional) {
    if (!j.is_object()) fail(path, "must be an object, got " + describe(j));
    std::vector<std::string_view> allowed = required;
    allowed.insert(allowed.end(), optional.begin(), optional.end());
    for (const auto& item : j.items())
        if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end())
            fail(path, fmt::format("unknown field {} (allowed: {})", json_quoted(item.key()),
                                   joined(allowed)));
    for (std::string_view key : required)
        if (!j.contains(key))
            fail(path, fmt::format("missing required field {}", json_quoted(key)));
}

const nlohmann::json& required(const nlohmann::json& j, const std::string& path,
                               std::string_view key) {
    if (!j.is_object()) fail(path, "must be an object, got " + describe(j));
    const nlohmann::json* value = optional(j, key);
    if (!value) fail(path, fmt::format("missing required field {}", json_quoted(key)));
    return *value;
}

const nlohmann::json* optional(const nlohmann::json& j, std::string_view key) {
    if (!j.is_object()) return nullptr;
    const auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
}

std::string text(const nlohmann::json& v, const std::string& path) {
    if (!v.is_string()) fail(path, "must be a string, got " + describe(v));
    return v.get<std::string>();
}

std::string non_empty_text(const nlohmann::json& v, const std::string& path) {
    std::string s = text(v, path);
    if (s.empty()) fail(path, "must not be empty");
    return s;
}

int64_t integer(const nlohmann::json& v, const std::string& path) {
    if (!v.is_number_integer()) fail(path, "must be an integer, got " + describe(v));
    if (v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX))
        fail(path, "is out of range, got " + describe(v));
    return v.get<int64_t>();
}

uint64_t unsigned_integer(const nlohmann::json& v, const std::string& path, uint64_t max) {
    if (!v.is_number_unsigned()) fail(path, "must be a non-negative integer, got " + describe(v));
    const uint64_t value = v.get<uint64_t>();
    if (value > max) fail(path, fmt::format("must be at most {}, got {}", max, value));
    return value;
}

double finite_number(const nlohmann::json& v, const std::string& path) {
    if (!v.is_number()) fail(path, "must be a number, got " + describe(v));
    const double number = v.get<double>();
    // The parser already refuses overflowing literals (1e999); this keeps the promise local.
    if (!std::isfinite(number)) fail(path, "must be a finite number, got " + describe(v));
    return number;
}

float finite_float(const nlohmann::json& v, const std::string& path) {
    const double number = finite_number(v, path);
    if (std::abs(number) > double(std::numeric_limits<float>::max()))
        fail(path, "is out of range for a 32-bit float, got " + describe(v));
    return float(number);
}

bool boolean(const nlohmann::json& v, const std::string& path) {
    if (!v.is_boolean()) fail(path, "must be true or false, got " + describe(v));
    return v.get<bool>();
}

const nlohmann::json& array(const nlohmann::json& v, const std::string& path) {
    if (!v.is_array()) fail(path, "must be an array, got " + describe(v));
    return v;
}

std::vector<std::string> texts(const nlohmann::json& v, const std::string& path) {
    std::vector<std::string> out;
    const nlohmann::json& list = array(v, path);
    for (size_t i = 0; i < list.size(); ++i) out.push_back(text(list[i], element(path, i)));
    return out;
}

std::string text(const nlohmann::json& j, const std::string& path, std::string_view key) {
    return text(required(j, path, key), field(path, key));
}

int64_t integer(const nlohmann::json& j, const std::string& path, std::string_view key) {
    return integer(required(j, path, key), field(path, key));
}

uint64_t unsigned_integer(const nlohmann::json& j, const std::string& path, std::string_view key,
                          uint64_t max) {
    return unsigned_integer(required(j, path, key), field(path, key), max);
}

float finite_float(const nlohmann::json& j, const std::string& path, std::string_view key) {
    return finite_float(required(j, path, key), field(path, key));
}

std::vector<std::string> texts(const nlohmann::json& j, const std::string& path,
                               std::string_view key) {
    return texts(required(j, path, key), field(path, key));
}

Error to_error(const JsonFieldError& e, std::string_view label) {
    Error error =
        make_error(e.code, e.path.empty() ? fmt::format("{}: {}", label, e.what)
                                          : fmt::format("{}: {}: {}", label, e.path, e.what));
    error.file = std::string(label);
    error.field = e.path;
    return error;
}

}  // namespace acetate::json_fields
