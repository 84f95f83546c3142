#pragma once
// What OpenEXR would otherwise trust in a file's header, checked on the bytes before it sees
// them: a header attribute declaring more bytes than the file holds (a 141-byte file once made
// OpenEXR allocate 2 GB for one string attribute), and a data window larger than any image the
// host accepts. Files that are not OpenEXR pass untouched.

#include <filesystem>
#include <string_view>

#include "core/result.hpp"

namespace acetate {

// Errors are one line, `<file>: EXR header: ...`.
Result<void> check_exr_header(std::string_view bytes, const std::filesystem::path& file,
                              int max_side);

}  // namespace acetate
