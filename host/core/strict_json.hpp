#pragma once
// Parsing JSON strictly, the same way for every JSON file the project reads (a scene, the
// registry, sign-offs, the harness's own files; docs/conventions.md, "Limits on inputs"):
// - a key written twice in one object is refused, anywhere in the document: nlohmann keeps
//   the last of two equal keys without a word, so a file could show a reviewer one value while
//   the program uses another;
// - a syntax error is one line with its line and column, without nlohmann's exception id or
//   its quote of the text it last read (which can be megabytes).
// Messages, both InvalidInput:
//   `<label>: malformed JSON: parse error at line 2, column 26: syntax error while parsing
//   object key - unexpected '}'; expected string literal`
//   `<label>: floors[0].tiles[0]: duplicate field "rect"` (`<label>: duplicate field "format"`
//   at the top level): the JSON path of the object holding the key, then the key.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>

#include "core/result.hpp"

namespace acetate {

// The document in `text`; `label` (usually the file name as given) starts every message.
Result<nlohmann::json> parse_json_strict(std::string_view text, std::string_view label);

// read_input_file (core/input_file.hpp) with its checks and `max_bytes`, then
// parse_json_strict labelled with the file name as given.
Result<nlohmann::json> read_json_file(const std::filesystem::path& file, std::uint64_t max_bytes,
                                      std::string_view what);

}  // namespace acetate
