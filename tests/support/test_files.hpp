#pragma once
// What every test program shares (defined once here, not per file): a scratch folder per test
// under the system temp directory, files and images written into it, and commands run and
// captured.

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/image_io.hpp"

namespace acetate::test {

// A fresh, empty folder named after the running test.
std::filesystem::path scratch_dir();

// Writes text to a file and returns its path.
std::filesystem::path write_text(const std::filesystem::path& file, const std::string& text);

// Writes an image as 32-bit float EXR (premultiplied; exact for any float), returns its path.
std::filesystem::path write_exr(const std::filesystem::path& file, const ImageRGBA& image);
// An 8-bit straight-alpha RGBA PNG holding exactly `rgba8`.
std::filesystem::path write_png8(const std::filesystem::path& file, uint32_t width, uint32_t height,
                                 const std::vector<uint8_t>& rgba8);

// A scene file with `edit` applied to its JSON, written as `out` with its tile images and masks
// made absolute, so it loads from any folder; returns `out`. For tests that compare a live or
// command-line change with the scene file saying the same.
std::filesystem::path write_edited_scene(const std::filesystem::path& scene,
                                         const std::function<void(nlohmann::json&)>& edit,
                                         const std::filesystem::path& out);

// ---- running commands ----------------------------------------------------------------------

// `text` in single quotes for sh.
std::string shell_quote(const std::string& text);

// Whether `text` holds `part` anywhere.
inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// A file's bytes ("" when it cannot be read).
std::string read_file(const std::filesystem::path& file);

// The non-empty lines of `text`.
std::vector<std::string> nonempty_lines(const std::string& text);

// What a command did: its exit status as sh reports it (128 + N when signal N ended it; -1
// when sh itself did not run) and everything it printed.
struct CommandResult {
    int code = -1;
    std::string out, err;
    std::string command;
    // The command, its status and its output, for a failing assertion's message.
    std::string describe() const;
};

// Runs `command` with sh, stdin from /dev/null, stdout and stderr captured through files in
// `capture_dir` (each call its own pair, so calls from several threads may share the folder).
// Variables for a command that runs acetate-harness: the Khronos validation layer on (so the
// vulkan-validation check is judged, not skipped), and shader caches that do not depend on
// the user's (ctest sets them to the build tree's test cache; else a private temp folder).
std::string harness_environment();

CommandResult run_command(const std::string& command, const std::filesystem::path& capture_dir);

}  // namespace acetate::test
