// Fuzzes the registry reader: any bytes give a registry or a one-line error; a registry that
// parses writes out as JSON that parses again to the same text.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "registry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto registry = acetate::Registry::parse(text, "fuzz/registry.json");
    if (!registry.ok()) {
        if (registry.error().message.find('\n') != std::string::npos) __builtin_trap();
        return 0;
    }
    const std::string written = registry->to_json();
    auto again = acetate::Registry::parse(written, "fuzz/registry.json (written)");
    if (!again.ok() || again->to_json() != written) __builtin_trap();
    return 0;
}
