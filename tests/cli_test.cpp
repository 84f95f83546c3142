// End-to-end tests of the `acetate` binary: bad input gives one line on stderr and a non-zero
// exit (never a crash), `--floors` names its outputs, `--stats` reports what the binding
// documents, and the bundled example renders cleanly in every view.
//
// Every run has Vulkan validation on (ACETATE_VALIDATION=1) and must print no validation line.

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

namespace acetate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Running the binary

std::string lower(std::string text) {
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
CliRun run_acetate(const fs::path& dir, const std::string& args) {
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
bool is_unvalidated_plugin_warning(const std::string& line) {
    return line.rfind("acetate: warning: loading unvalidated plugin ", 0) == 0;
}

// No Vulkan validation message and no sign of a crash.
void expect_clean_stderr(const CliRun& run) {
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
void expect_refused(const CliRun& run, const std::vector<std::string>& names) {
    EXPECT_TRUE(run.exited) << "killed by a signal?\n" << run.describe();
    EXPECT_TRUE(run.code == 1 || run.code == 2) << run.describe();
    expect_clean_stderr(run);
    const std::vector<std::string> lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << "expected exactly one line on stderr\n" << run.describe();
    for (const std::string& name : names)
        EXPECT_NE(lines[0].find(name), std::string::npos)
            << "the error line does not name \"" << name << "\": " << lines[0];
}

void expect_success(const CliRun& run) {
    EXPECT_TRUE(run.exited && run.code == 0) << run.describe();
    expect_clean_stderr(run);
}

// ---------------------------------------------------------------------------------------------
// Scenes

// A premultiplied image of one colour.
ImageRGBA solid(uint32_t w, uint32_t h, float r, float g, float b, float a) {
    ImageRGBA image(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float* p = image.at(x, y);
            p[0] = r * a, p[1] = g * a, p[2] = b * a, p[3] = a;
        }
    return image;
}

// The images of the two-floor scene: an opaque ground and a half-transparent upper tile.
void write_tile_images(const fs::path& dir) {
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
fs::path write_scene(const SceneText& scene = {}) {
    const fs::path dir = test::scratch_dir();
    write_tile_images(dir);
    test::write_text(dir / "scene.json", scene.text());
    return dir;
}

// ---------------------------------------------------------------------------------------------
// (a) Bad input: one line on stderr naming the file and the field, non-zero exit, no crash.

TEST(CliBadInput, MissingSceneFile) {
    const fs::path dir = test::scratch_dir();
    const CliRun run = run_acetate(dir, "render no_such_scene.json -o out.png");
    expect_refused(run, {"no_such_scene.json"});
    EXPECT_NE(lower(run.err).find("not found"), std::string::npos) << run.describe();
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, MalformedJson) {
    const fs::path dir = test::scratch_dir();
    write_tile_images(dir);
    test::write_text(dir / "scene.json",
                     "{ \"format\": \"acetate-scene/1\",\n  \"canvas\": { \"width\": 64, \n");
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    expect_refused(run, {"scene.json", "line"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, UnknownField) {
    SceneText scene;
    scene.upper_tile = R"({ "image": "b.exr", "rect": [8, 4, 16, 16], "opacity": 0.5 })";
    const fs::path dir = write_scene(scene);
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    expect_refused(run, {"scene.json", "floors[1].tiles[0]", "opacity"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, UnknownTopLevelField) {
    SceneText scene;
    scene.root_extra = R"(, "activ_floor": 0)";
    const fs::path dir = write_scene(scene);
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    expect_refused(run, {"scene.json", "activ_floor"});
}

TEST(CliBadInput, NegativeTileSize) {
    SceneText scene;
    scene.upper_tile = R"({ "image": "b.exr", "rect": [8, 4, -5, 16] })";
    const fs::path dir = write_scene(scene);
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    expect_refused(run, {"scene.json", "floors[1].tiles[0].rect[2]", "-5"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, NegativeTileHeight) {
    SceneText scene;
    scene.ground_tile = R"({ "image": "a.exr", "rect": [0, 0, 64, -1] })";
    const fs::path dir = write_scene(scene);
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    expect_refused(run, {"scene.json", "floors[0].tiles[0].rect[3]"});
}

TEST(CliBadInput, MissingImageFile) {
    SceneText scene;
    scene.upper_tile = R"({ "image": "missing.exr", "rect": [8, 4, 16, 16] })";
    const fs::path dir = write_scene(scene);
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    expect_refused(run, {"scene.json", "floors[1].tiles[0].image", "missing.exr"});
}

TEST(CliBadInput, ImageThatCannotBeDecoded) {
    SceneText scene;
    scene.upper_tile = R"({ "image": "x.png", "rect": [8, 4, 16, 16] })";
    const fs::path dir = write_scene(scene);
    test::write_text(dir / "x.png", std::string("this is not a PNG \x01\x02\x03 garbage"));
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    // The line must name the image file and the scene field that refers to it, so that the
    // author knows which tile to fix.
    expect_refused(run, {"x.png", "floors[1].tiles[0].image"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, CanvasLargerThanTheDeviceAllows) {
    SceneText scene;
    scene.canvas = R"("width": 20000, "height": 32)";
    const fs::path dir = write_scene(scene);
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    expect_refused(run, {"scene.json", "canvas", "20000"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, SceneNamingAFloorPlugin) {
    SceneText scene;
    scene.upper_extra = R"(, "effects": [ { "plugin": "com.example.glow", "params": {} } ])";
    const fs::path dir = write_scene(scene);
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    expect_refused(run, {"scene.json", "floors[1].effects[0]", "com.example.glow"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, SceneNamingAGlobalPlugin) {
    SceneText scene;
    scene.root_extra = R"(, "global_effects": [ { "plugin": "com.example.haze" } ])";
    const fs::path dir = write_scene(scene);
    const CliRun run = run_acetate(dir, "render scene.json -o out.png");
    expect_refused(run, {"scene.json", "global_effects[0]", "com.example.haze"});
}

TEST(CliBadInput, BadView) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --view sparkle");
    expect_refused(run, {"--view", "sparkle"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, BadFormat) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --format rgb8");
    expect_refused(run, {"--format", "rgb8"});
}

TEST(CliBadInput, FloorOutOfRange) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --floor 5");
    expect_refused(run, {"--floor", "5"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, FloorsListWithAnOutOfRangeFloor) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --floors 0,1,7");
    expect_refused(run, {"--floors", "7"});
    // Nothing is rendered when any requested floor is bad.
    EXPECT_FALSE(fs::exists(dir / "out.floor0.png"));
    EXPECT_FALSE(fs::exists(dir / "out.floor1.png"));
}

TEST(CliBadInput, FloorsListThatIsNotAList) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --floors 0,x");
    expect_refused(run, {"--floors", "0,x"});
}

TEST(CliBadInput, EmptyFloorsList) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --floors ''");
    expect_refused(run, {"--floors"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, TimeThatIsNotAFiniteNumber) {
    for (const char* time : {"nan", "inf", "-inf", "1e39"}) {
        const fs::path dir = write_scene();
        const CliRun run =
            run_acetate(dir, std::string("render scene.json -o out.png --time ") + time);
        expect_refused(run, {"--time"});
        EXPECT_FALSE(fs::exists(dir / "out.png")) << time;
    }
}

TEST(CliBadInput, UppercaseOutputExtension) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.PNG");
    expect_refused(run, {"out.PNG", ".png"});
    EXPECT_FALSE(fs::exists(dir / "out.PNG"));
}

// Outputs never destroy inputs: each refusal names both files, and the input is unchanged.
TEST(CliBadInput, OutputOntoATileImage) {
    const fs::path dir = write_scene();
    const std::string before = test::read_file(dir / "a.exr");
    const CliRun run = run_acetate(dir, "render scene.json -o a.exr");
    expect_refused(run, {"-o", "a.exr", "floors[0].tiles[0].image"});
    EXPECT_EQ(test::read_file(dir / "a.exr"), before);
}

TEST(CliBadInput, OutputOntoATileImageThroughALink) {
    const fs::path dir = write_scene();
    fs::create_symlink(dir / "a.exr", dir / "link.exr");
    const std::string before = test::read_file(dir / "a.exr");
    const CliRun run = run_acetate(dir, "render scene.json -o link.exr");
    expect_refused(run, {"link.exr", "a.exr"});
    EXPECT_EQ(test::read_file(dir / "a.exr"), before);
}

TEST(CliBadInput, StatsOntoTheScene) {
    const fs::path dir = write_scene();
    const std::string before = test::read_file(dir / "scene.json");
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --stats ./scene.json");
    expect_refused(run, {"--stats", "scene.json"});
    EXPECT_EQ(test::read_file(dir / "scene.json"), before);
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, OutputAndStatsOnOnePath) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --stats out.png");
    expect_refused(run, {"--stats", "out.png", "-o"});
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(CliBadInput, UnsupportedOutputExtension) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.bmp");
    expect_refused(run, {"out.bmp"});
    EXPECT_FALSE(fs::exists(dir / "out.bmp"));
}

// ---------------------------------------------------------------------------------------------
// (b) --floors names one output per floor

TEST(CliFloors, OneFilePerFloorWithTheIndexBeforeTheExtension) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --floors 0,1,0");
    expect_success(run);
    EXPECT_TRUE(fs::exists(dir / "out.floor0.png")) << run.describe();
    EXPECT_TRUE(fs::exists(dir / "out.floor1.png")) << run.describe();
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    EXPECT_FALSE(fs::exists(dir / "out.floor2.png"));

    auto floor0 = load_image(dir / "out.floor0.png", ImageRole::Colour);
    auto floor1 = load_image(dir / "out.floor1.png", ImageRole::Colour);
    ASSERT_TRUE(floor0) << floor0.error().message;
    ASSERT_TRUE(floor1) << floor1.error().message;
    ASSERT_EQ(floor0->width, 64u);
    ASSERT_EQ(floor0->height, 32u);
    ASSERT_EQ(floor1->width, 64u);
    ASSERT_EQ(floor1->height, 32u);
    // Inside the upper tile the two frames differ; outside it they agree.
    const float* in0 = floor0->at(12, 8);
    const float* in1 = floor1->at(12, 8);
    EXPECT_GT(std::fabs(in0[0] - in1[0]) + std::fabs(in0[1] - in1[1]) + std::fabs(in0[2] - in1[2]),
              0.1f);
    const float* out0 = floor0->at(40, 24);
    const float* out1 = floor1->at(40, 24);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(out0[c], out1[c], 1e-6f) << "channel " << c;
}

TEST(CliFloors, ExrOutputsAreNamedTheSameWay) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o render.exr --floors 1,0");
    expect_success(run);
    EXPECT_TRUE(fs::exists(dir / "render.floor0.exr")) << run.describe();
    EXPECT_TRUE(fs::exists(dir / "render.floor1.exr")) << run.describe();
    EXPECT_FALSE(fs::exists(dir / "render.exr"));
}

TEST(CliFloors, AllRendersEveryFloorBottomToTop) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --floors all");
    expect_success(run);
    // The scene has two floors: both, in order, and nothing else.
    EXPECT_TRUE(fs::exists(dir / "out.floor0.png")) << run.describe();
    EXPECT_TRUE(fs::exists(dir / "out.floor1.png")) << run.describe();
    EXPECT_FALSE(fs::exists(dir / "out.floor2.png"));
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    EXPECT_LT(run.out.find("floor 0:"), run.out.find("floor 1:")) << run.describe();
}

TEST(CliFloors, SingleFloorWritesTheOutputItself) {
    const fs::path dir = write_scene();
    const CliRun run = run_acetate(dir, "render scene.json -o out.png --floor 0");
    expect_success(run);
    EXPECT_TRUE(fs::exists(dir / "out.png")) << run.describe();
    EXPECT_FALSE(fs::exists(dir / "out.floor0.png"));
}

// ---------------------------------------------------------------------------------------------
// (c) --stats

void expect_count(const json& object, const char* key, const std::string& where) {
    ASSERT_TRUE(object.contains(key)) << where << " has no \"" << key << "\": " << object.dump();
    EXPECT_TRUE(object[key].is_number_integer()) << where << "." << key << " = " << object[key];
    if (object[key].is_number_integer()) {
        EXPECT_GE(object[key].get<int64_t>(), 0) << where << "." << key;
    }
}

TEST(CliStats, ReportsLoadFramesAndTargets) {
    const fs::path dir = write_scene();
    const CliRun run =
        run_acetate(dir, "render scene.json -o out.png --floors 0,1,0 --stats stats.json");
    expect_success(run);
    ASSERT_TRUE(fs::exists(dir / "stats.json")) << run.describe();
    json stats;
    ASSERT_NO_THROW(stats = json::parse(test::read_file(dir / "stats.json")));

    ASSERT_TRUE(stats.contains("device"));
    ASSERT_TRUE(stats["device"].is_string());
    EXPECT_FALSE(stats["device"].get<std::string>().empty());
    ASSERT_TRUE(stats.contains("load_milliseconds"));
    ASSERT_TRUE(stats["load_milliseconds"].is_number());
    EXPECT_GT(stats["load_milliseconds"].get<double>(), 0.0);

    ASSERT_TRUE(stats.contains("frames"));
    ASSERT_TRUE(stats["frames"].is_array());
    ASSERT_EQ(stats["frames"].size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        const json& frame = stats["frames"][i];
        const std::string where = "frames[" + std::to_string(i) + "]";
        ASSERT_TRUE(frame.is_object()) << where;
        ASSERT_TRUE(frame.contains("milliseconds")) << where;
        ASSERT_TRUE(frame["milliseconds"].is_number()) << where;
        EXPECT_GE(frame["milliseconds"].get<double>(), 0.0) << where;
        for (const char* key :
             {"passes", "pixels_shaded", "images_loaded", "render_targets_allocated",
              "shaders_compiled", "pipelines_created", "premultiplied_violations"})
            expect_count(frame, key, where);
        if (HasFailure()) return;
        EXPECT_GT(frame["passes"].get<int64_t>(), 0) << where;
        EXPECT_GT(frame["pixels_shaded"].get<int64_t>(), 0) << where;
        EXPECT_EQ(frame["premultiplied_violations"].get<int64_t>(), 0) << where;
    }
    // Frames 2 and 3 (floors 1 and 0 again) are warm: nothing loaded, allocated or compiled.
    for (size_t i = 1; i < 3; ++i) {
        const json& frame = stats["frames"][i];
        const std::string where = "frames[" + std::to_string(i) + "]";
        EXPECT_EQ(frame["images_loaded"].get<int64_t>(), 0) << where;
        EXPECT_EQ(frame["render_targets_allocated"].get<int64_t>(), 0) << where;
        EXPECT_EQ(frame["shaders_compiled"].get<int64_t>(), 0) << where;
        EXPECT_EQ(frame["pipelines_created"].get<int64_t>(), 0) << where;
    }
    // Floor 1 shades more than floor 0 alone; floor 0 twice shades the same.
    EXPECT_GT(stats["frames"][1]["pixels_shaded"].get<int64_t>(),
              stats["frames"][0]["pixels_shaded"].get<int64_t>());
    EXPECT_EQ(stats["frames"][2]["pixels_shaded"], stats["frames"][0]["pixels_shaded"]);
    EXPECT_EQ(stats["frames"][2]["passes"], stats["frames"][0]["passes"]);

    ASSERT_TRUE(stats.contains("render_targets"));
    ASSERT_TRUE(stats["render_targets"].is_array());
    EXPECT_FALSE(stats["render_targets"].empty());
    for (size_t i = 0; i < stats["render_targets"].size(); ++i) {
        const json& target = stats["render_targets"][i];
        const std::string where = "render_targets[" + std::to_string(i) + "]";
        ASSERT_TRUE(target.contains("name")) << where << ": " << target.dump();
        ASSERT_TRUE(target.contains("format")) << where << ": " << target.dump();
        ASSERT_TRUE(target.contains("width")) << where << ": " << target.dump();
        ASSERT_TRUE(target.contains("height")) << where << ": " << target.dump();
        EXPECT_TRUE(target["name"].is_string()) << where;
        EXPECT_FALSE(target["name"].get<std::string>().empty()) << where;
        EXPECT_TRUE(target["format"].is_string()) << where;
        ASSERT_TRUE(target["width"].is_number_integer()) << where;
        ASSERT_TRUE(target["height"].is_number_integer()) << where;
        EXPECT_GT(target["width"].get<int64_t>(), 0) << where;
        EXPECT_LE(target["width"].get<int64_t>(), 64) << where;
        EXPECT_GT(target["height"].get<int64_t>(), 0) << where;
        EXPECT_LE(target["height"].get<int64_t>(), 32) << where;
    }
}

// ---------------------------------------------------------------------------------------------
// (d) The bundled example renders in every view, to PNG and EXR, with no violations.

const char* const kViews[] = {"normal",    "floor-alpha", "accum-alpha",
                              "floor-rgb", "violations",  "isolation"};

class HarbourView : public ::testing::TestWithParam<const char*> {};

fs::path harbour_scene() {
    return fs::path(ACETATE_EXAMPLES_DIR) / "harbour" / "scene.json";
}

uint64_t total_violations(const json& stats) {
    uint64_t total = 0;
    for (const json& frame : stats.at("frames"))
        total += frame.at("premultiplied_violations").get<uint64_t>();
    return total;
}

TEST_P(HarbourView, RendersToPngAndExrWithoutViolations) {
    const fs::path scene = harbour_scene();
    ASSERT_TRUE(fs::is_regular_file(scene)) << "the bundled example is missing: " << scene;
    const std::string view = GetParam();
    const fs::path dir = test::scratch_dir();
    for (const char* ext : {".png", ".exr"}) {
        SCOPED_TRACE(std::string("output ") + ext);
        const std::string out = "harbour" + std::string(ext);
        const std::string stats_file = "stats" + std::string(ext) + ".json";
        // The harbour's plugins are the build's, validated or not: the host policy is
        // tested in cli_policy_test.cpp.
        const CliRun run = run_acetate(dir, "render " + test::shell_quote(scene.string()) + " -o " +
                                                out + " --view " + view + " --stats " + stats_file +
                                                " --allow-unvalidated");
        expect_success(run);
        ASSERT_TRUE(fs::exists(dir / out)) << run.describe();
        ASSERT_TRUE(fs::exists(dir / stats_file)) << run.describe();
        json stats;
        ASSERT_NO_THROW(stats = json::parse(test::read_file(dir / stats_file)));
        ASSERT_TRUE(stats.contains("frames")) << stats.dump();
        ASSERT_FALSE(stats["frames"].empty());
        EXPECT_EQ(total_violations(stats), 0u) << stats.dump(2);

        auto image = load_image(dir / out, ImageRole::Colour);
        ASSERT_TRUE(image) << image.error().message;
        EXPECT_GT(image->width, 0u);
        EXPECT_GT(image->height, 0u);
        // load_image refuses non-finite pixels; a == 0 must carry rgb == 0.
        uint64_t bad = 0;
        for (size_t i = 0; i + 3 < image->pixels.size(); i += 4)
            if (image->pixels[i + 3] == 0.0f &&
                (image->pixels[i] != 0.0f || image->pixels[i + 1] != 0.0f ||
                 image->pixels[i + 2] != 0.0f))
                ++bad;
        EXPECT_EQ(bad, 0u) << "pixels with a == 0 and rgb != 0 in " << out;
    }
}

INSTANTIATE_TEST_SUITE_P(AllViews, HarbourView, ::testing::ValuesIn(kViews),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                             std::string name = info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace acetate

// ---------------------------------------------------------------------------------------------
// A hostile registry: a FIFO given as --registry is refused at once, not waited on forever.
// (Appended as its own block, includes and all, so it touches no other test.)

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

namespace acetate {
namespace {

TEST(CliBadInput, FifoRegistryIsRefusedAtOnce) {
    SceneText scene;  // it names a plugin, so the registry is read
    scene.upper_extra = R"(, "effects": [ { "plugin": "com.example.glow" } ])";
    const fs::path dir = write_scene(scene);
    const fs::path fifo = dir / "registry.fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    // A host blocked on the FIFO is released after 10 s (a writer comes and goes, so it reads
    // end of file): the test then fails on the time taken instead of hanging.
    std::atomic<bool> done{false};
    std::thread watchdog([&] {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (!done && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        while (!done) {
            if (const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC); fd >= 0)
                ::close(fd);
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
    });
    const auto start = std::chrono::steady_clock::now();
    const CliRun run = run_acetate(dir, "render scene.json --registry registry.fifo -o out.png");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    done = true;
    watchdog.join();
    expect_refused(run, {"acetate: registry.fifo: not a regular file (a FIFO)"});
    EXPECT_EQ(run.code, 1) << run.describe();
    EXPECT_LT(seconds, 5.0) << "the registry is refused before anything waits on it";
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

}  // namespace
}  // namespace acetate
