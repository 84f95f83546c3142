// End-to-end tests of the `acetate` binary's outputs: `--floors` names one file per floor,
// `--times` one per time, `--stats` reports what the binding documents, and the bundled example
// renders cleanly in every view, to PNG and EXR.
//
// Every run has Vulkan validation on (ACETATE_VALIDATION=1) and must print no validation line.

#include "cli_fixtures.hpp"

namespace acetate {
namespace {

using namespace cli_test;

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
// --times: one process renders a floor at several times

fs::path fire_quay_scene() {
    return fs::path(ACETATE_EXAMPLES_DIR).parent_path() / "validation" / "references" /
           "acetate.fire" / "scenes" / "quay.json";
}

TEST(CliTimes, OneFilePerTimeEachAsASeparateRunAtThatTimeWouldWrite) {
    const fs::path dir = test::scratch_dir();
    const std::string scene = test::shell_quote(fire_quay_scene().string());
    const CliRun run = run_acetate(dir, "render " + scene +
                                            " -o anim.png --times 0:1:1/2 --stats stats.json "
                                            "--allow-unvalidated");
    expect_success(run);
    for (const char* name : {"anim.frame0000.png", "anim.frame0001.png", "anim.frame0002.png"})
        EXPECT_TRUE(fs::exists(dir / name)) << name << "\n" << run.describe();
    EXPECT_FALSE(fs::exists(dir / "anim.png"));
    EXPECT_FALSE(fs::exists(dir / "anim.frame0003.png"));
    json stats;
    ASSERT_NO_THROW(stats = json::parse(test::read_file(dir / "stats.json")));
    ASSERT_EQ(stats.at("frames").size(), 3u);
    EXPECT_EQ(stats["frames"][0].at("time"), 0.0);
    EXPECT_EQ(stats["frames"][1].at("time"), 0.5);
    EXPECT_EQ(stats["frames"][2].at("time"), 1.0);
    // Each frame is a pure function of its time: the same bytes as a process of its own.
    const CliRun alone =
        run_acetate(dir, "render " + scene + " -o alone.png --time 0.5 --allow-unvalidated");
    expect_success(alone);
    EXPECT_EQ(test::read_file(dir / "alone.png"), test::read_file(dir / "anim.frame0001.png"));
    // The fire moves: the frames are not all one picture.
    EXPECT_NE(test::read_file(dir / "anim.frame0000.png"),
              test::read_file(dir / "anim.frame0001.png"));
}

TEST(CliTimes, ABadListIsOneLineAndWritesNothing) {
    const fs::path dir = write_scene();
    for (const auto& [times, expected] : std::vector<std::pair<std::string, std::string>>{
             {"0:1:0", "--times: step \"0\": must be above 0"},
             {"1:0:1", "--times: the range ends (0) before it starts (1)"},
             {"0,nan", "--times: must be a finite number, got \"nan\""},
             {"0:1:1/0", "the divisor must be above 0"},
             {"0:1:1/2/3", "expected S or N/D"},
             {"0:1e9:1", "at most 100000 in one run"},
             {"0:1", "expected START:END:STEP"}}) {
        SCOPED_TRACE(times);
        const CliRun run = run_acetate(dir, "render scene.json -o out.png --times " + times);
        EXPECT_EQ(run.code, 2) << run.describe();
        expect_refused(run, {expected});
    }
    const CliRun both = run_acetate(dir, "render scene.json -o out.png --times 0,1 --time 1");
    EXPECT_EQ(both.code, 2) << both.describe();
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    EXPECT_FALSE(fs::exists(dir / "out.frame0000.png"));
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
              "shaders_compiled", "pipelines_created", "barriers", "premultiplied_violations"})
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
    // Barriers are the plan's: the same floor again records as many; every frame records at
    // least the one that makes its writes visible to the host.
    EXPECT_EQ(stats["frames"][2]["barriers"], stats["frames"][0]["barriers"]);
    EXPECT_GT(stats["frames"][0]["barriers"].get<int64_t>(), 1);

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
