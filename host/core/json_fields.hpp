#pragma once
// The one reader of JSON fields, for every JSON file and message the project reads: a scene,
// the registry, a case's spec and result (the harness's child protocol), shards, reference
// manifests. Errors name the field by its JSON path ("floors[0].tiles[1].rect",
// "plugins[2].review.at") and read the same everywhere:
//   `<label>: <object path>: unknown field "imgae" (allowed: image, rect, masks)`
//   `<label>: <object path>: missing required field "rect"`
//   `<label>: <field path>: must be a string, got 3`
// A reader is straight-line code: a check that fails throws JsonFieldError, and read_json
// catches it once, at the reader's entry point, where it becomes a Result. Nothing else
// throws or catches it. Keys and values come from the file and may hold any character; a
// message stays one line (control characters are written as escapes).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/result.hpp"

namespace acetate::json_fields {

struct JsonFieldError {
    std::string path, what;
    ErrorCode code = ErrorCode::InvalidInput;
};

[[noreturn]] void fail(const std::string& path, std::string what,
                       ErrorCode code = ErrorCode::InvalidInput);

// "a.b" for key b of path a ("b" at the top level), and "a[3]" for element 3.
std::string field(const std::string& path, std::string_view key);
std::string element(const std::string& path, size_t index);
// A short, single-line rendering of a value for "got ..." (a type name for arrays and objects).
std::string describe(const nlohmann::json& value);
// `text` as a JSON string literal, quotes and escapes included.
std::string json_quoted(std::string_view text);

// `j` is an object with every `required` key and no key outside `required` and `optional`:
// a misspelt field is an error, not a silently defaulted value.
void expect_object(const nlohmann::json& j, const std::string& path,
                   const std::vector<std::string_view>& required,
                   const std::vector<std::string_view>& optional = {});
// Key `key` of the object `j` at `path`; required() fails when it is missing.
const nlohmann::json& required(const nlohmann::json& j, const std::string& path,
                               std::string_view key);
const nlohmann::json* optional(const nlohmann::json& j, std::string_view key);

// Typed values; `path` names the value itself.
std::string text(const nlohmann::json& v, const std::string& path);
std::string non_empty_text(const nlohmann::json& v, const std::string& path);
int64_t integer(const nlohmann::json& v, const std::string& path);
// A non-negative integer no larger than `max`.
uint64_t unsigned_integer(const nlohmann::json& v, const std::string& path,
                          uint64_t max = UINT64_MAX);
double finite_number(const nlohmann::json& v, const std::string& path);
float finite_float(const nlohmann::json& v, const std::string& path);  // in the 32-bit float range
bool boolean(const nlohmann::json& v, const std::string& path);
const nlohmann::json& array(const nlohmann::json& v, const std::string& path);
std::vector<std::string> texts(const nlohmann::json& v,
                               const std::string& path);  // an array of strings

// The same for the required key `key` of the object `j` at `path`.
std::string text(const nlohmann::json& j, const std::string& path, std::string_view key);
int64_t integer(const nlohmann::json& j, const std::string& path, std::string_view key);
uint64_t unsigned_integer(const nlohmann::json& j, const std::string& path, std::string_view key,
                          uint64_t max = UINT64_MAX);
float finite_float(const nlohmann::json& j, const std::string& path, std::string_view key);
std::vector<std::string> texts(const nlohmann::json& j, const std::string& path,
                               std::string_view key);

// "<label>: <path>: <what>", or "<label>: <what>" at the top level.
Error to_error(const JsonFieldError& e, std::string_view label);

// Runs `read()` and returns what it returns, or its field error as one line starting with
// `label` (the file's name as given, or "child.json").
template <class Read>
auto read_json(std::string_view label, Read&& read) -> Result<decltype(read())> {
    try {
        if constexpr (std::is_void_v<decltype(read())>) {
            std::forward<Read>(read)();
            return {};
        } else {
            return std::forward<Read>(read)();
        }
    } catch (const JsonFieldError& e) {
        return to_error(e, label);
    }
}

}  // namespace acetate::json_fields
