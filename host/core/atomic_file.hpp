#pragma once
// Writing files so that a reader never sees half of one: write a temporary sibling, flush it to
// disk, rename it over the target. rename() within one directory is atomic on POSIX.

#include <filesystem>
#include <string_view>

#include "core/result.hpp"

namespace acetate {

// A temporary name next to `file`, unique within this process: `<stem>.tmp-<pid>-<n><ext>`.
// The extension stays last because writers such as OpenImageIO pick the format from it.
std::filesystem::path temp_sibling(const std::filesystem::path& file);

// Writes `bytes` to `file` atomically (temp sibling, fsync, rename). On failure `file` is
// untouched and no temporary is left behind; the error names `file`.
Result<void> write_file_atomically(const std::filesystem::path& file, std::string_view bytes);

// Finishes an atomic write whose temporary was produced by another writer: fsyncs `temp` and
// renames it over `file`. On failure `temp` is removed and the error names `file`.
Result<void> replace_with_temp(const std::filesystem::path& temp,
                               const std::filesystem::path& file);

}  // namespace acetate
