#pragma once
// What libpng would otherwise trust in a file, checked on the bytes before it sees them: a chunk
// declaring more bytes than the file holds. libpng allocates what a chunk declares before it
// reads it (a 239-byte file declaring a 1.8 GB text chunk took 6 to 14 s to refuse, found by
// the image fuzzer). Files that are not PNG pass untouched.

#include <filesystem>
#include <string_view>

#include "core/result.hpp"

namespace acetate {

// Errors are one line, `<file>: PNG chunk ...`.
Result<void> check_png_chunks(std::string_view bytes, const std::filesystem::path& file);

}  // namespace acetate
