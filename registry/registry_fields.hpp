#pragma once
// The shapes of a registry's fields and the refusals every registry operation shares: ids,
// versions, hashes, times (used by registry.cpp, registry_json.cpp and registry_trust.cpp).

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "core/result.hpp"
#include "registry.hpp"

namespace acetate::registry_fields {

// Verdicts that make a run fail; evidence records passing runs only.
inline constexpr std::array<const char*, 4> kFailingVerdicts = {"FAIL", "FLAKY", "CRASH",
                                                                "TIMEOUT"};

bool is_hex64(std::string_view s);
// "MAJOR.MINOR.PATCH", each a decimal uint32 without sign.
std::optional<std::array<uint32_t, 3>> parse_version(std::string_view s);
// ISO-8601 UTC to the second: 2025-11-22T08:51:00Z.
bool is_timestamp(const std::string& s);
// YYYY-MM-DD.
bool is_day(const std::string& s);
bool is_blank(std::string_view s);
// The first 12 hex digits, as messages and the readable copy show hashes.
std::string short_hash(std::string_view hash);
// "ID VERSION"
std::string plugin_name(std::string_view id, std::string_view version);
// InvalidInput: "ID VERSION: what".
Error refused(std::string_view id, std::string_view version, const std::string& what);
// Io: "FILE: what: strerror(err)".
Error io_error(const std::filesystem::path& file, std::string_view what, int err);
ValidationStage next(ValidationStage s);
// The registry's order: by id, then by version numerically.
bool entry_less(const RegistryEntry& a, const RegistryEntry& b);

}  // namespace acetate::registry_fields
