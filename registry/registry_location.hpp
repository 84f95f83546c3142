#pragma once
// Which registry file a tool uses, and which committed sign-offs `validate` imports. The
// harness and `acetate render` resolve them the same way, so what the harness records is what
// the host reads (docs/registry.md, "Where the registry lives").
//
// Registry: `--registry FILE`, else $ACETATE_REGISTRY, else
//   - a program run from its build tree (build/host/acetate): <build>/validation/registry.json;
//   - an installed program (PREFIX/bin/acetate): $XDG_DATA_HOME/acetate/registry.json, else
//     $HOME/.local/share/acetate/registry.json (the XDG base-directory default).
// Allowed signers (the maintainers' public keys, which verify every sign-off):
//   `--allowed-signers FILE`, else $ACETATE_ALLOWED_SIGNERS, else the source tree's
//   validation/allowed_signers (build tree) or PREFIX/share/acetate/validation/allowed_signers
//   (installed); revoked keys are read from `revoked_keys` beside that file.
// Sign-offs: `--signoffs FILE`, else the source tree's validation/signoffs.json (build tree) or
// PREFIX/share/acetate/validation/signoffs.json (installed); none if that file is missing.

#include <filesystem>
#include <optional>

namespace acetate {

// True when the running program is the one in the build tree it was compiled in, false when it
// was installed (or copied) anywhere else.
bool running_from_build_tree();

std::filesystem::path registry_path(const std::optional<std::filesystem::path>& flag);
// The registry used when neither --registry nor $ACETATE_REGISTRY is given.
std::filesystem::path default_registry_path();
// The allowed-signers file every reader of the registry verifies sign-offs with.
std::filesystem::path allowed_signers_path(const std::optional<std::filesystem::path>& flag);
// The golden references' root (<root>/<plugin id>/manifest.json): `--references DIR`, else
// $ACETATE_REFERENCES, else the source tree's validation/references (build tree) or
// PREFIX/share/acetate/validation/references (installed).
std::filesystem::path references_path(const std::optional<std::filesystem::path>& flag);
// The committed sign-offs `validate` imports by default, if that file exists.
std::optional<std::filesystem::path> default_signoffs_path();
// VALIDATION-REGISTRY.md beside the registry file.
std::filesystem::path registry_markdown_path(const std::filesystem::path& registry);

}  // namespace acetate
