// End-to-end tests of the `acetate` binary on bad input: each gives one line on stderr and a
// non-zero exit (never a crash), and writes nothing. Outputs, floors, statistics and the
// example in every view are in cli_outputs_test.cpp.
//
// Every run has Vulkan validation on (ACETATE_VALIDATION=1) and must print no validation line.

#include "cli_fixtures.hpp"

namespace acetate {
namespace {

using namespace cli_test;

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

// A 24-bit BMP (OpenImageIO reads it; the host itself reads only PNG and EXR): `size` x `size`
// pixels of one grey, rows bottom up, each padded to four bytes.
std::string bmp_file(uint32_t size, uint8_t grey) {
    const uint32_t row = (size * 3 + 3) / 4 * 4, pixels = row * size;
    auto le32 = [](uint32_t v) {
        return std::string{char(v), char(v >> 8), char(v >> 16), char(v >> 24)};
    };
    std::string bytes = "BM" + le32(54 + pixels) + le32(0) + le32(54);
    bytes += le32(40) + le32(size) + le32(size) + std::string("\x01\0\x18\0", 4) + le32(0) +
             le32(pixels) + le32(2835) + le32(2835) + le32(0) + le32(0);
    for (uint32_t y = 0; y < size; ++y)
        bytes += std::string(size * 3, char(grey)) + std::string(row - size * 3, '\0');
    return bytes;
}

// Formats other than PNG and EXR are a module the host library loads from its own folder
// (host/scene/image_codec.hpp). A host library copied without it still renders a scene of EXR
// tiles to PNG; a BMP tile is refused in one line naming the module that is missing.
TEST(CliBadInput, AHostLibraryWithoutItsImageCodecReadsOnlyPngAndExr) {
    const fs::path dir = write_scene();
    const fs::path alone = dir / "host-alone";
    fs::create_directories(alone);
    fs::copy_file(ACETATE_HOST_LIBRARY, alone / fs::path(ACETATE_HOST_LIBRARY).filename());
    test::write_text(dir / "c.bmp", bmp_file(8, 128));
    SceneText bmp;
    bmp.upper_tile = R"({ "image": "c.bmp", "rect": [8, 4, 16, 16] })";
    test::write_text(dir / "bmp.json", bmp.text());
    // Searched before the program's run path, so this copy is the host library it loads.
    ASSERT_EQ(::setenv("LD_LIBRARY_PATH", alone.c_str(), 1), 0);
    const CliRun exr = run_acetate(dir, "render scene.json -o out.png");
    const CliRun other = run_acetate(dir, "render bmp.json -o bmp.png");
    ::unsetenv("LD_LIBRARY_PATH");
    expect_success(exr);
    EXPECT_TRUE(fs::exists(dir / "out.png"));
    expect_refused(
        other, {"bmp.json", "floors[1].tiles[0].image", "c.bmp",
                "cannot load the image codec " + (alone / "libacetate-image-codec.so").string()});
    EXPECT_FALSE(fs::exists(dir / "bmp.png"));
    // With the module beside the host library, as built, the BMP tile renders.
    expect_success(run_acetate(dir, "render bmp.json -o bmp.png"));
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
