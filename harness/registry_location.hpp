#pragma once
// Which registry file a tool uses: `--registry FILE`, else $ACETATE_REGISTRY, else the build
// tree's own (<build>/validation/registry.json, fixed at configure time). The harness and
// `acetate render` resolve it the same way, so what the harness records is what the host reads.

#include <filesystem>
#include <optional>

namespace acetate {

std::filesystem::path registry_path(const std::optional<std::filesystem::path>& flag);
// VALIDATION-REGISTRY.md beside the registry file.
std::filesystem::path registry_markdown_path(const std::filesystem::path& registry);

}  // namespace acetate
