#pragma once
// Reading only the entries a host needs (docs/registry.md, "Host policy"): a host about to load
// one binary needs the registry's entries for that binary and that plugin id, not the other
// thousands. This scan finds where each element of the top-level "plugins" array begins and
// ends, at memory speed and without building a document, so only the entries a caller selects
// are parsed (strictly, as every registry read is).
//
// It understands exactly the shape the registry writes: one object with "format" and
// "plugins". Anything else, a syntax error included, is nullopt: the caller then reads the
// whole file with the full reader, which refuses a bad file with its usual one-line message.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace acetate {

struct RegistryText {
    std::string format;                     // the "format" member, unescaped if plain
    std::vector<std::string_view> entries;  // each element of "plugins", as written
};

std::optional<RegistryText> scan_registry(std::string_view json_text);

}  // namespace acetate
