#pragma once
// Scratch files for tests: each test gets its own folder under the system temp directory.

#include <filesystem>
#include <string>

#include "scene/image_io.hpp"

namespace acetate::test {

// A fresh, empty folder named after the running test.
std::filesystem::path scratch_dir();

// Writes text to a file and returns its path.
std::filesystem::path write_text(const std::filesystem::path& file, const std::string& text);

// Writes an image as 32-bit float EXR (premultiplied; exact for any float), returns its path.
std::filesystem::path write_exr(const std::filesystem::path& file, const ImageRGBA& image);

}  // namespace acetate::test
