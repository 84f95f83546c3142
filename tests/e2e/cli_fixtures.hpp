#pragma once
// What the `acetate` end-to-end tests share: running the built binary in a folder with
// validation on and its output captured, the checks on what it printed (a refusal is one line,
// a success prints no validation line), and small scenes with their tile images.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "scene/image_io.hpp"
#include "test_files.hpp"

namespace acetate::cli_test {

namespace fs = std::filesystem;
using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Running the binary

inline std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

struct CliRun {
    int raw_status = -1;
    bool exited = false;  // ended by exit(), not by a signal
    int code = -1;        // WEXITSTATUS when exited
    std::string out, err;
    std::string command;

    std::string describe() const {
        return "command: " + command + "\nexit code: " + std::to_string(code) +
               (exited ? "" : " (did not exit normally)") + "\n--- stdout ---\n" + out +
               "--- stderr ---\n" + err;
    }
};

// Runs `acetate ARGS` in `dir`, capturing stdout and stderr separately.
inline CliRun run_acetate(const fs::path& dir, const std::string& args) {
    static int counter = 0;
    const fs::path out_file = dir / ("cli-stdout-" + std::to_string(counter) + ".txt");
    const fs::path err_file = dir / ("cli-stderr-" + std::to_string(counter) + ".txt");
    ++counter;
    // Mesa and XDG caches are private to the test run (ctest sets them; otherwise a folder under
    // the temp directory). Mesa does not create missing parents and says so on stderr, which
    // would add a line to every run, so the folders are made here.
    const fs::path fallback = fs::temp_directory_path() / "acetate-cli-test-cache";
    const char* mesa_env = std::getenv("MESA_SHADER_CACHE_DIR");
    const char* xdg_env = std::getenv("XDG_CACHE_HOME");
    const fs::path mesa = mesa_env && *mesa_env ? fs::path(mesa_env) : fallback / "mesa";
    const fs::path xdg = xdg_env && *xdg_env ? fs::path(xdg_env) : fallback / "xdg";
    std::error_code ec;
    fs::create_directories(mesa, ec);
    fs::create_directories(xdg, ec);
    CliRun run;
    run.command =
        "cd " + test::shell_quote(dir.string()) +
        " && ACETATE_VALIDATION=1 MESA_SHADER_CACHE_DIR=" + test::shell_quote(mesa.string()) +
        " XDG_CACHE_HOME=" + test::shell_quote(xdg.string()) + " " +
        test::shell_quote(ACETATE_CLI_PATH) + " " + args;
    const std::string shell = run.command + " >" + test::shell_quote(out_file.string()) + " 2>" +
                              test::shell_quote(err_file.string()) + " </dev/null";
    run.raw_status = std::system(shell.c_str());
    run.exited = run.raw_status != -1 && WIFEXITED(run.raw_status);
    run.code = run.exited ? WEXITSTATUS(run.raw_status) : -1;
    run.out = test::read_file(out_file);
    run.err = test::read_file(err_file);
    return run;
}

// The host policy's warning for a plugin loaded with --allow-unvalidated (these tests use the
// built plugins, which the registry need not have validated). It names the registry file,
// whose default path (<build>/validation/registry.json) would read as a validation message.
inline bool is_unvalidated_plugin_warning(const std::string& line) {
    return line.rfind("acetate: warning: loading unvalidated plugin ", 0) == 0;
}

// No Vulkan validation message and no sign of a crash.
inline void expect_clean_stderr(const CliRun& run) {
    for (const std::string& line : test::nonempty_lines(run.err)) {
        if (is_unvalidated_plugin_warning(line)) continue;
        EXPECT_EQ(lower(line).find("validation"), std::string::npos)
            << "validation message on stderr: " << line << "\n"
            << run.describe();
    }
    for (const char* crash : {"Segmentation", "core dumped", "Aborted", "terminate called",
                              "Assertion", "AddressSanitizer"})
        EXPECT_EQ(run.err.find(crash), std::string::npos) << crash << "\n" << run.describe();
}

// A refused input: exit status 1 or 2 (not a signal, not 0), exactly one line on stderr that
// contains every one of `names`, and nothing written to the output.
inline void expect_refused(const CliRun& run, const std::vector<std::string>& names) {
    EXPECT_TRUE(run.exited) << "killed by a signal?\n" << run.describe();
    EXPECT_TRUE(run.code == 1 || run.code == 2) << run.describe();
    expect_clean_stderr(run);
    const std::vector<std::string> lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << "expected exactly one line on stderr\n" << run.describe();
    for (const std::string& name : names)
        EXPECT_NE(lines[0].find(name), std::string::npos)
            << "the error line does not name \"" << name << "\": " << lines[0];
}

inline void expect_success(const CliRun& run) {
    EXPECT_TRUE(run.exited && run.code == 0) << run.describe();
    expect_clean_stderr(run);
}

// ---------------------------------------------------------------------------------------------
// Scenes

// A premultiplied image of one colour.
inline ImageRGBA solid(uint32_t w, uint32_t h, float r, float g, float b, float a) {
    ImageRGBA image(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float* p = image.at(x, y);
            p[0] = r * a, p[1] = g * a, p[2] = b * a, p[3] = a;
        }
    return image;
}

// The images of the two-floor scene: an opaque ground and a half-transparent upper tile.
inline void write_tile_images(const fs::path& dir) {
    test::write_exr(dir / "a.exr", solid(4, 4, 0.2f, 0.5f, 0.1f, 1.0f));
    test::write_exr(dir / "b.exr", solid(4, 4, 0.9f, 0.2f, 0.3f, 0.5f));
}

struct SceneText {
    std::string canvas = R"("width": 64, "height": 32, "background": [0.05, 0.05, 0.06, 1.0])";
    std::string ground_tile = R"({ "image": "a.exr", "rect": [0, 0, 64, 32] })";
    std::string upper_tile = R"({ "image": "b.exr", "rect": [8, 4, 16, 16] })";
    std::string upper_extra;  // e.g. `, "effects": [...]`
    std::string root_extra;   // e.g. `, "global_effects": [...]`

    std::string text() const {
        return R"({ "format": "acetate-scene/1", "canvas": { )" + canvas + R"( },
  "floors": [ { "name": "ground", "tiles": [ )" +
               ground_tile + R"( ] },
              { "name": "upper", "tiles": [ )" +
               upper_tile + R"( ])" + upper_extra + R"( } ],
  "active_floor": 1)" +
               root_extra + " }\n";
    }
};

// Writes images and scene.json into a fresh folder; returns the folder.
inline fs::path write_scene(const SceneText& scene = {}) {
    const fs::path dir = test::scratch_dir();
    write_tile_images(dir);
    test::write_text(dir / "scene.json", scene.text());
    return dir;
}

}  // namespace acetate::cli_test
