// Scene parsing: the format's example scene parses with resolved paths and defaults; every kind of
// bad input gives one line naming the file, the JSON path and what is wrong.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <future>
#include <stdexcept>
#include <string>
#include <thread>

#include "core/input_file.hpp"
#include "scene/scene.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The example scene of the format's specification, verbatim.
constexpr const char* kExample = R"({ "format": "acetate-scene/1",
  "canvas": { "width": 1280, "height": 720, "background": [0.05, 0.05, 0.06, 1.0] },
  "floors": [
    { "name": "ground",
      "tiles": [ { "image": "ground.png", "rect": [0, 0, 1280, 720], "masks": { "water": "ground_Water.png" } } ],
      "lights": [ { "pos": [400, 300], "radius": 250, "color": [1.0, 0.8, 0.6], "intensity": 2.0 } ],
      "effects": [] },
    { "name": "upper", "tiles": [ { "image": "roof.png", "rect": [200, 100, 600, 400] } ], "effects": [] } ],
  "global_effects": [],
  "active_floor": 1 })";

class SceneParseTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        // Only existence is checked at parse time, so the images need no real pixels.
        for (const char* name : {"ground.png", "ground_Water.png", "roof.png"})
            test::write_text(dir_ / name, "not decoded at parse time");
        scene_ = json::parse(kExample);
    }

    fs::path file() const { return dir_ / "scene.json"; }

    Result<SceneDesc> parse() {
        test::write_text(file(), scene_.dump(2));
        return parse_scene_file(file());
    }

    // Parses scene_, expects failure, returns the message (and checks it is one line).
    std::string error_message(ErrorCode expected_code = ErrorCode::InvalidInput) {
        auto result = parse();
        if (result.ok()) {
            ADD_FAILURE() << "parse succeeded, expected an error";
            return "";
        }
        EXPECT_EQ(result.error().code, expected_code) << result.error().message;
        EXPECT_EQ(result.error().message.find('\n'), std::string::npos);
        return result.error().message;
    }

    // What every message must look like: `<file>: <json path>: <what>`.
    std::string expected(const std::string& rest) const { return file().string() + ": " + rest; }

    fs::path dir_;
    json scene_;
};

TEST_F(SceneParseTest, ExampleParsesWithResolvedPaths) {
    auto result = parse();
    ASSERT_TRUE(result.ok()) << result.error().message;
    const SceneDesc& scene = result.value();
    EXPECT_EQ(scene.file, file());
    EXPECT_EQ(scene.width, 1280u);
    EXPECT_EQ(scene.height, 720u);
    EXPECT_FLOAT_EQ(scene.background[0], 0.05f);
    EXPECT_FLOAT_EQ(scene.background[2], 0.06f);
    EXPECT_FLOAT_EQ(scene.background[3], 1.0f);
    ASSERT_EQ(scene.floors.size(), 2u);
    EXPECT_EQ(scene.floors[0].name, "ground");
    EXPECT_EQ(scene.floors[1].name, "upper");
    EXPECT_EQ(scene.active_floor, 1u);

    ASSERT_EQ(scene.floors[0].tiles.size(), 1u);
    const TileDesc& ground = scene.floors[0].tiles[0];
    EXPECT_EQ(ground.image, dir_ / "ground.png");
    EXPECT_TRUE(ground.image.is_absolute());
    ASSERT_EQ(ground.masks.size(), 1u);
    EXPECT_EQ(ground.masks.at("water"), dir_ / "ground_Water.png");

    const SceneRect& roof = scene.floors[1].tiles[0].rect;
    EXPECT_EQ(roof.x, 200);
    EXPECT_EQ(roof.y, 100);
    EXPECT_EQ(roof.width, 600);
    EXPECT_EQ(roof.height, 400);

    ASSERT_EQ(scene.floors[0].lights.size(), 1u);
    const LightDesc& light = scene.floors[0].lights[0];
    EXPECT_FLOAT_EQ(light.pos[0], 400);
    EXPECT_FLOAT_EQ(light.pos[1], 300);
    EXPECT_FLOAT_EQ(light.radius, 250);
    EXPECT_FLOAT_EQ(light.color[1], 0.8f);
    EXPECT_FLOAT_EQ(light.intensity, 2.0f);
    EXPECT_TRUE(scene.floors[1].lights.empty());
    EXPECT_TRUE(scene.global_effects.empty());
}

TEST_F(SceneParseTest, OptionalFieldsTakeTheirDefaults) {
    scene_["canvas"].erase("background");
    scene_.erase("active_floor");
    scene_.erase("global_effects");
    scene_["floors"][0].erase("effects");
    scene_["floors"][0]["tiles"][0].erase("masks");
    scene_["floors"][0]["lights"][0] = json::parse(R"({"pos": [1, 2], "radius": 3})");
    auto result = parse();
    ASSERT_TRUE(result.ok()) << result.error().message;
    const SceneDesc& scene = result.value();
    EXPECT_EQ(scene.background, (std::array<float, 4>{0, 0, 0, 1}));
    EXPECT_EQ(scene.active_floor, 1u) << "defaults to the top floor";
    EXPECT_TRUE(scene.floors[0].tiles[0].masks.empty());
    EXPECT_EQ(scene.floors[0].lights[0].color, (std::array<float, 3>{1, 1, 1}));
    EXPECT_FLOAT_EQ(scene.floors[0].lights[0].intensity, 1.0f);
}

TEST_F(SceneParseTest, PathsAreLexicallyNormalAndAbsolutePathsKept) {
    fs::create_directories(dir_ / "sub");
    scene_["floors"][1]["tiles"][0]["image"] = "./sub/../roof.png";
    scene_["floors"][0]["tiles"][0]["image"] = (dir_ / "ground.png").string();
    auto result = parse();
    ASSERT_TRUE(result.ok()) << result.error().message;
    EXPECT_EQ(result->floors[1].tiles[0].image, dir_ / "roof.png");
    EXPECT_EQ(result->floors[0].tiles[0].image, dir_ / "ground.png");
}

TEST_F(SceneParseTest, EffectsAreKeptWithWhereTheyCameFrom) {
    scene_["floors"][1]["effects"] = json::parse(
        R"([{"plugin": "acetate.bloom", "params": {"strength": 0.5}, "preset": "high"}])");
    scene_["global_effects"] = json::parse(R"([{"plugin": "acetate.grade"}])");
    auto result = parse();
    ASSERT_TRUE(result.ok()) << result.error().message;
    ASSERT_EQ(result->floors[1].effects.size(), 1u);
    const EffectRef& bloom = result->floors[1].effects[0];
    EXPECT_EQ(bloom.plugin, "acetate.bloom");
    EXPECT_EQ(bloom.params, json::parse(R"({"strength": 0.5})"));
    EXPECT_EQ(bloom.preset, "high");
    EXPECT_EQ(bloom.where, "floors[1].effects[0]");
    ASSERT_EQ(result->global_effects.size(), 1u);
    EXPECT_EQ(result->global_effects[0].where, "global_effects[0]");
    EXPECT_TRUE(result->global_effects[0].preset.empty());
    EXPECT_EQ(result->global_effects[0].params, json::object());
}

TEST_F(SceneParseTest, MissingSceneFileIsFileNotFound) {
    const fs::path missing = dir_ / "nope.json";
    auto result = parse_scene_file(missing);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, ErrorCode::FileNotFound);
    EXPECT_EQ(result.error().message, missing.string() + ": file not found: " + missing.string());
}

TEST_F(SceneParseTest, MalformedJsonGivesThePosition) {
    test::write_text(file(),
                     "{\"format\": \"acetate-scene/1\",\n  \"canvas\": {\"width\": 10,}\n}");
    auto result = parse_scene_file(file());
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, ErrorCode::InvalidInput);
    const std::string& message = result.error().message;
    EXPECT_EQ(message.rfind(expected("malformed JSON: parse error at line 2, column 26"), 0), 0u)
        << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST_F(SceneParseTest, EmptyFileIsMalformed) {
    test::write_text(file(), "");
    auto result = parse_scene_file(file());
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message.rfind(expected("malformed JSON: "), 0), 0u)
        << result.error().message;
}

TEST_F(SceneParseTest, UnknownFieldsAreRejectedAtEveryLevel) {
    struct Case {
        json::json_pointer where;
        std::string expected;
    };
    const Case cases[] = {
        {json::json_pointer(""),
         "unknown field \"extra\" (allowed: format, canvas, floors, global_effects, active_floor)"},
        {json::json_pointer("/canvas"),
         "canvas: unknown field \"extra\" (allowed: width, height, background)"},
        {json::json_pointer("/floors/1"),
         "floors[1]: unknown field \"extra\" (allowed: name, tiles, lights, sun, effects)"},
        {json::json_pointer("/floors/0/lights/0"),
         "floors[0].lights[0]: unknown field \"extra\" (allowed: pos, radius, color, intensity, "
         "height)"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.expected);
        SetUp();
        scene_[c.where]["extra"] = 1;
        EXPECT_EQ(error_message(), expected(c.expected));
    }
}

TEST_F(SceneParseTest, MisspeltTileFieldIsNamed) {
    json& tile = scene_["floors"][0]["tiles"][0];
    tile["imgae"] = tile["image"];
    tile.erase("image");
    EXPECT_EQ(
        error_message(),
        expected("floors[0].tiles[0]: unknown field \"imgae\" (allowed: image, rect, masks)"));
}

TEST_F(SceneParseTest, UnknownEffectFieldIsNamed) {
    scene_["global_effects"] =
        json::parse(R"([{"plugin": "acetate.bloom", "preset": "high", "qualty": 1}])");
    EXPECT_EQ(error_message(), expected("global_effects[0]: unknown field \"qualty\" "
                                        "(allowed: plugin, params, preset)"));
}

TEST_F(SceneParseTest, DuplicateJsonKeyIsRejected) {
    test::write_text(file(), R"({"format": "acetate-scene/1", "canvas": {"width": 4, "height": 4},
        "floors": [{"name": "a", "tiles": [{"image": "roof.png", "rect": [0, 0, 1, 1],
                                            "rect": [0, 0, 2, 2]}]}]})");
    auto result = parse_scene_file(file());
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message, expected("floors[0].tiles[0]: duplicate field \"rect\""));
}

TEST_F(SceneParseTest, TileSizeMustBePositive) {
    scene_["floors"][1]["tiles"][0]["rect"][2] = -5;
    EXPECT_EQ(error_message(), expected("floors[1].tiles[0].rect[2]: width must be > 0, got -5"));
    SetUp();
    scene_["floors"][1]["tiles"][0]["rect"][3] = 0;
    EXPECT_EQ(error_message(), expected("floors[1].tiles[0].rect[3]: height must be > 0, got 0"));
    SetUp();
    scene_["floors"][1]["tiles"][0]["rect"] = json::array({0, 0, 5});
    EXPECT_EQ(error_message(), expected("floors[1].tiles[0].rect: must be an array of 4 numbers "
                                        "[x, y, width, height], got 3 elements"));
    SetUp();
    scene_["floors"][1]["tiles"][0]["rect"][0] = "left";
    EXPECT_EQ(error_message(),
              expected("floors[1].tiles[0].rect[0]: must be a number, got \"left\""));
}

// The GPU takes 32-bit floats: numbers it cannot hold as pixels are refused at parse time.
TEST_F(SceneParseTest, TileRectStaysWithinFloatPixels) {
    const std::pair<std::pair<int, double>, std::string> cases[] = {
        {{0, 1e308},
         "floors[1].tiles[0].rect[0]: must lie within +-16777216 scene pixels (2^24, where 32-bit "
         "floats still hold whole pixels), got 1e+308"},
        {{1, -1e39},
         "floors[1].tiles[0].rect[1]: must lie within +-16777216 scene pixels (2^24, where 32-bit "
         "floats still hold whole pixels), got -1e+39"},
        {{2, 1e-300}, "floors[1].tiles[0].rect[2]: width must be at least 1/256 pixel, got 1e-300"},
        {{3, 0.001}, "floors[1].tiles[0].rect[3]: height must be at least 1/256 pixel, got 0.001"},
    };
    for (const auto& [change, message] : cases) {
        SCOPED_TRACE(message);
        SetUp();
        scene_["floors"][1]["tiles"][0]["rect"][change.first] = change.second;
        EXPECT_EQ(error_message(), expected(message));
    }
    SetUp();
    scene_["floors"][1]["tiles"][0]["rect"] =
        json::array({-16777216.0, 16777216.0, 0.5, 1.0 / 256});
    EXPECT_TRUE(parse().ok()) << "the limits themselves are allowed";
}

TEST_F(SceneParseTest, LightsPerFloorAreLimited) {
    json lights = json::array();
    for (int i = 0; i < 4097; ++i) lights.push_back({{"pos", {i, 0}}, {"radius", 5}});
    scene_["floors"][0]["lights"] = lights;
    EXPECT_EQ(error_message(),
              expected("floors[0].lights: 4097 lights is over the limit of 4096 per floor"));
    SetUp();
    lights.erase(lights.size() - 1);
    scene_["floors"][0]["lights"] = lights;
    EXPECT_TRUE(parse().ok()) << "4096 lights are allowed";
}

TEST_F(SceneParseTest, OverflowingNumberIsMalformed) {
    test::write_text(file(), R"({"format": "acetate-scene/1", "canvas": {"width": 4, "height": 4},
        "floors": [{"name": "a", "tiles": [{"image": "roof.png", "rect": [1e999, 0, 1, 1]}]}]})");
    auto result = parse_scene_file(file());
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message, expected("malformed JSON: number overflow parsing '1e999'"));
}

TEST_F(SceneParseTest, CanvasSizeMustBeAPositiveInteger) {
    const std::pair<json, std::string> cases[] = {
        {0, "canvas.width: must be > 0, got 0"},
        {-3, "canvas.width: must be > 0, got -3"},
        {640.5, "canvas.width: must be a positive integer, got 640.5"},
        {"640", "canvas.width: must be a positive integer, got \"640\""},
        {70000, "canvas.width: must be <= 65536, got 70000"},
    };
    for (const auto& [width, message] : cases) {
        SCOPED_TRACE(message);
        SetUp();
        scene_["canvas"]["width"] = width;
        EXPECT_EQ(error_message(), expected(message));
    }
    SetUp();
    scene_["canvas"].erase("height");
    EXPECT_EQ(error_message(), expected("canvas: missing required field \"height\""));
}

TEST_F(SceneParseTest, BackgroundIsChecked) {
    scene_["canvas"]["background"][3] = 1.5;
    EXPECT_EQ(error_message(), expected("canvas.background[3]: alpha must be in [0, 1], got 1.5"));
    SetUp();
    scene_["canvas"]["background"] = json::array({0, 0, 0});
    EXPECT_EQ(error_message(), expected("canvas.background: must be an array of 4 numbers "
                                        "[r, g, b, a], got 3 elements"));
}

TEST_F(SceneParseTest, ActiveFloorMustNameAFloor) {
    scene_["active_floor"] = 2;
    EXPECT_EQ(error_message(), expected("active_floor: must be < 2 (the number of floors), got 2"));
    SetUp();
    scene_["active_floor"] = -1;
    EXPECT_EQ(error_message(), expected("active_floor: must be >= 0, got -1"));
    SetUp();
    scene_["active_floor"] = "upper";
    EXPECT_EQ(error_message(), expected("active_floor: must be an integer, got \"upper\""));
}

TEST_F(SceneParseTest, FloorsAreRequiredAndNamedUniquely) {
    scene_["floors"][1]["name"] = "ground";
    EXPECT_EQ(error_message(),
              expected("floors[1].name: duplicate floor name \"ground\" (also floors[0].name)"));
    SetUp();
    scene_["floors"] = json::array();
    EXPECT_EQ(error_message(), expected("floors: at least one floor is required"));
    SetUp();
    scene_["floors"][0].erase("name");
    EXPECT_EQ(error_message(), expected("floors[0]: missing required field \"name\""));
    SetUp();
    scene_["floors"][0]["name"] = "";
    EXPECT_EQ(error_message(), expected("floors[0].name: must not be empty"));
}

TEST_F(SceneParseTest, MissingImageNamesTheResolvedPath) {
    fs::remove(dir_ / "roof.png");
    EXPECT_EQ(
        error_message(ErrorCode::FileNotFound),
        expected("floors[1].tiles[0].image: file not found: " + (dir_ / "roof.png").string()));
}

TEST_F(SceneParseTest, MissingMaskNamesTheResolvedPath) {
    fs::remove(dir_ / "ground_Water.png");
    EXPECT_EQ(error_message(ErrorCode::FileNotFound),
              expected("floors[0].tiles[0].masks.water: file not found: " +
                       (dir_ / "ground_Water.png").string()));
}

TEST_F(SceneParseTest, MaskKindMustBeLowercaseIdentifier) {
    scene_["floors"][0]["tiles"][0]["masks"] = json::parse(R"({"Water": "ground_Water.png"})");
    EXPECT_EQ(error_message(), expected("floors[0].tiles[0].masks: invalid mask kind \"Water\": "
                                        "use lowercase letters, digits and _"));
}

TEST_F(SceneParseTest, FormatMustBeExactlyTheSupportedOne) {
    scene_["format"] = "acetate-scene/2";
    EXPECT_EQ(error_message(), expected("format: unsupported format \"acetate-scene/2\" "
                                        "(supported: \"acetate-scene/1\")"));
    SetUp();
    scene_.erase("format");
    EXPECT_EQ(error_message(), expected("missing required field \"format\""));
}

TEST_F(SceneParseTest, InvalidLightsAreNamed) {
    const std::pair<json, std::string> cases[] = {
        {json::parse(R"({"pos": [0, 0], "radius": 0})"),
         "floors[0].lights[0].radius: must be > 0, got 0"},
        {json::parse(R"({"pos": [0, 0], "radius": 5, "intensity": -1})"),
         "floors[0].lights[0].intensity: must be >= 0, got -1"},
        {json::parse(R"({"pos": [0, 0], "radius": 5, "color": [1, -0.5, 0]})"),
         "floors[0].lights[0].color[1]: must be >= 0, got -0.5"},
        {json::parse(R"({"pos": [0, 0], "radius": 5, "color": [1, 1]})"),
         "floors[0].lights[0].color: must be an array of 3 numbers [r, g, b], got 2 elements"},
        {json::parse(R"({"pos": [0], "radius": 5})"),
         "floors[0].lights[0].pos: must be an array of 2 numbers [x, y], got 1 elements"},
        {json::parse(R"({"radius": 5})"), "floors[0].lights[0]: missing required field \"pos\""},
    };
    for (const auto& [light, message] : cases) {
        SCOPED_TRACE(message);
        SetUp();
        scene_["floors"][0]["lights"][0] = light;
        EXPECT_EQ(error_message(), expected(message));
    }
}

TEST_F(SceneParseTest, WrongTypesAreNamed) {
    scene_["floors"][0]["tiles"] = json::object();
    EXPECT_EQ(error_message(), expected("floors[0].tiles: must be an array, got object"));
    SetUp();
    scene_["floors"][1]["effects"] = json::array({json::parse(R"({"plugin": 7})")});
    EXPECT_EQ(error_message(), expected("floors[1].effects[0].plugin: must be a string, got 7"));
}

TEST_F(SceneParseTest, MessagesUseTheFileNameAsGiven) {
    // A name relative to the working directory, whose images do not exist there.
    auto result = parse_scene_text(scene_.dump(), "relative/scene.json");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message.rfind("relative/scene.json: floors[0].tiles[0].image: "
                                           "file not found: /",
                                           0),
              0u)
        << result.error().message;
}

// ---- hostile files --------------------------------------------------------------------------

TEST_F(SceneParseTest, SceneOverTheSizeLimitIsRefusedBeforeParsing) {
    // Sparse: one byte over the limit takes no disk and, refused by its size, no time.
    test::write_text(file(), "");
    ASSERT_EQ(::truncate(file().c_str(), off_t(kMaxSceneFileBytes + 1)), 0);
    static_assert(kMaxSceneFileBytes == 16 << 20, "the message below states the limit");
    const auto start = std::chrono::steady_clock::now();
    auto result = parse_scene_file(file());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(result.error().message,
              expected("16.0 MiB (16777217 bytes) is over the 16 MiB limit for a scene file"));
    EXPECT_LT(seconds, 0.5) << "refused by its size, before reading";
}

TEST_F(SceneParseTest, FifoSceneIsRefusedWithoutBlocking) {
    ASSERT_EQ(::mkfifo(file().c_str(), 0600), 0) << std::strerror(errno);
    auto parsing = std::async(std::launch::async, [&] { return parse_scene_file(file()); });
    if (parsing.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
        ADD_FAILURE() << "parse_scene_file blocked on a FIFO";
        // Releases the blocked reader: it sees a writer come and go, then end of file.
        for (int i = 0; i < 1000; ++i) {
            const int fd = ::open(file().c_str(), O_WRONLY | O_NONBLOCK);
            if (fd >= 0) {
                ::close(fd);
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    }
    auto result = parsing.get();
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(result.error().message, expected("not a regular file (a FIFO)"));
}

TEST_F(SceneParseTest, DirectorySceneIsRefused) {
    fs::create_directories(file());
    auto result = parse_scene_file(file());
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(result.error().message, expected("not a regular file (a directory)"));
}

// Makes `depth` nested folders named `component` inside `dir`, working from descriptors
// (the full path is too long for the kernel to take), and writes `text` into `leaf` in the
// innermost one. Returns the path of that file relative to `dir`.
fs::path write_deep_file(const fs::path& dir, const std::string& component, int depth,
                         const std::string& leaf, const std::string& text) {
    fs::path relative;
    int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    for (int i = 0; i < depth && fd >= 0; ++i) {
        ::mkdirat(fd, component.c_str(), 0755);
        const int inner = ::openat(fd, component.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        ::close(fd);
        fd = inner;
        relative /= component;
    }
    if (fd < 0) throw std::runtime_error("cannot make nested folders in " + dir.string());
    const int out = ::openat(fd, leaf.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    ::close(fd);
    if (out < 0 || ::write(out, text.data(), text.size()) != ssize_t(text.size()))
        throw std::runtime_error("cannot write the nested file");
    ::close(out);
    return relative / leaf;
}

// The end of a long message: enough to see what it says, without pages of path.
std::string tail_of(const std::string& message) {
    return message.size() > 160 ? "..." + message.substr(message.size() - 160) : message;
}

TEST_F(SceneParseTest, ExistingPathLongerThanPathMaxIsNotFileNotFound) {
    const std::string component(200, 'd');
    const int depth = PATH_MAX / int(component.size()) + 2;
    const fs::path deep = dir_ / write_deep_file(dir_, component, depth, "scene.json", "{}");
    ASSERT_GT(deep.string().size(), size_t(PATH_MAX));
    auto result = parse_scene_file(deep);
    ASSERT_FALSE(result.ok());
    EXPECT_NE(result.error().code, ErrorCode::FileNotFound);
    EXPECT_TRUE(result.error().message == deep.string() + ": cannot open: File name too long")
        << tail_of(result.error().message);

    // The same for an image the scene names.
    const fs::path image = write_deep_file(dir_, component, depth, "roof.png", "not decoded");
    scene_["floors"][1]["tiles"][0]["image"] = image.string();
    auto named = parse();
    ASSERT_FALSE(named.ok());
    EXPECT_NE(named.error().code, ErrorCode::FileNotFound);
    EXPECT_TRUE(named.error().message == expected("floors[1].tiles[0].image: cannot check " +
                                                  (dir_ / image).string() + ": File name too long"))
        << tail_of(named.error().message);
}

}  // namespace
// The sun at the edges the format allows: the direction is exact where the angle is a
// multiple of 90 degrees (radians are not: cos(pi / 2) is 6.1e-17), so an effect that tests for
// a sun overhead or on an axis sees exactly that.
TEST(SunDirection, IsExactAtMultiplesOfNinetyDegrees) {
    using V = std::array<float, 3>;
    for (float azimuth : {0.0f, 30.0f, 90.0f, 217.5f, 359.0f})
        EXPECT_EQ((SunDesc{azimuth, 90}.direction()), (V{0, 0, 1})) << azimuth;
    EXPECT_EQ((SunDesc{0, 0}.direction()), (V{1, 0, 0}));
    EXPECT_EQ((SunDesc{90, 0}.direction()), (V{0, 1, 0}));
    EXPECT_EQ((SunDesc{180, 0}.direction()), (V{-1, 0, 0}));
    EXPECT_EQ((SunDesc{270, 0}.direction()), (V{0, -1, 0}));
    EXPECT_EQ((SunDesc{360, 0}.direction()), (V{1, 0, 0}));
    // Elsewhere, the ordinary unit vector.
    const V d = SunDesc{30, 40}.direction();
    const double pi = 3.14159265358979323846;
    EXPECT_NEAR(d[0], std::cos(40 * pi / 180) * std::cos(30 * pi / 180), 1e-7);
    EXPECT_NEAR(d[1], std::cos(40 * pi / 180) * std::sin(30 * pi / 180), 1e-7);
    EXPECT_NEAR(d[2], std::sin(40 * pi / 180), 1e-7);
}

}  // namespace acetate
