#pragma once
// Reading JSON files the harness owns (the registry, a case's result) with errors that name
// the field: a reader throws JsonFieldError with the field's path ("plugins[2].review.at")
// and catches it once, at its entry point, where it becomes a Result. Nothing else throws it.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace acetate::json_fields {

struct JsonFieldError {
    std::string path, what;
};

[[noreturn]] void fail(const std::string& path, std::string what);
// "a.b" for key b of path a ("b" at the top level), and "a[3]" for element 3.
std::string field(const std::string& path, std::string_view key);
std::string element(const std::string& path, size_t index);
// `j` is an object with every `required` key and no key outside `required` and `optional`:
// a misspelt field is an error, not a silently defaulted value.
void expect_object(const nlohmann::json& j, const std::string& path,
                   const std::vector<std::string_view>& required,
                   const std::vector<std::string_view>& optional = {});

}  // namespace acetate::json_fields
