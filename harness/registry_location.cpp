#include "registry_location.hpp"

#include <cstdlib>

namespace acetate {

std::filesystem::path registry_path(const std::optional<std::filesystem::path>& flag) {
    if (flag && !flag->empty()) return *flag;
    if (const char* env = std::getenv("ACETATE_REGISTRY"); env && *env) return env;
    return ACETATE_DEFAULT_REGISTRY;
}

std::filesystem::path registry_markdown_path(const std::filesystem::path& registry) {
    return registry.parent_path() / "VALIDATION-REGISTRY.md";
}

}  // namespace acetate
