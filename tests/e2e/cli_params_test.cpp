// End-to-end tests of `acetate render --param` and `--preset`: the image is byte for byte what
// the scene file edited to say the same renders, whichever way the effect is named; a bad flag
// is one line, before the device starts where it can be, and writes nothing.
//
// Every run has Vulkan validation on (ACETATE_VALIDATION=1) and must print no validation line.

#include "cli_fixtures.hpp"

namespace acetate {
namespace {

using namespace cli_test;

fs::path reference_scene(const std::string& plugin) {
    return fs::path(ACETATE_EXAMPLES_DIR).parent_path() / "validation" / "references" / plugin /
           "scenes" / "quay.json";
}

// The reference scene with `edit` applied, written into `dir` as `name` (image paths made
// absolute). The runs read their scenes from the scratch folder, so no message carries the word
// "validation" of the source tree's path, which the fixture takes for a Vulkan validation
// message.
fs::path edited_scene(const fs::path& dir, const std::string& plugin,
                      const std::function<void(json&)>& edit,
                      const std::string& name = "edited.json") {
    return test::write_edited_scene(reference_scene(plugin), edit, dir / name);
}

// expect_refused, with the warnings --allow-unvalidated prints at load set aside.
void expect_refused_after_warnings(const CliRun& run, const std::string& expected) {
    std::vector<std::string> lines;
    for (const std::string& line : test::nonempty_lines(run.err))
        if (!is_unvalidated_plugin_warning(line)) lines.push_back(line);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    EXPECT_NE(lines[0].find(expected), std::string::npos) << lines[0];
    expect_clean_stderr(run);
}

std::string quoted(const fs::path& file) {
    return test::shell_quote(file.string());
}

TEST(CliParams, AParameterSetOnTheCommandLineRendersAsTheEditedFileDoes) {
    const fs::path dir = test::scratch_dir();
    const fs::path edited = edited_scene(dir, "acetate.lighting", [](json& s) {
        s["floors"][0]["effects"][0]["params"]["day"] = 0.9;
    });
    expect_success(
        run_acetate(dir, "render " + quoted(edited) + " -o edited.png --allow-unvalidated"));
    const std::string scene = quoted(edited_scene(
        dir, "acetate.lighting", [](json&) {}, "scene.json"));
    for (const std::string param : {"quay.acetate.lighting.day=0.9", "0.0.day=0.9"}) {
        SCOPED_TRACE(param);
        const CliRun run = run_acetate(
            dir, "render " + scene + " -o flag.png --param " + param + " --allow-unvalidated");
        expect_success(run);
        EXPECT_EQ(test::read_file(dir / "flag.png"), test::read_file(dir / "edited.png"));
    }
    const CliRun plain = run_acetate(dir, "render " + scene + " -o plain.png --allow-unvalidated");
    expect_success(plain);
    EXPECT_NE(test::read_file(dir / "plain.png"), test::read_file(dir / "edited.png"))
        << "the parameter changes the picture";
}

TEST(CliParams, APresetAndAParameterOfAGlobalEffect) {
    const fs::path dir = test::scratch_dir();
    const fs::path edited = edited_scene(dir, "acetate.bloom", [](json& s) {
        s["global_effects"][0]["preset"] = "low";
        s["global_effects"][0]["params"]["threshold"] = 0.4;
    });
    expect_success(
        run_acetate(dir, "render " + quoted(edited) + " -o edited.png --allow-unvalidated"));
    const CliRun run = run_acetate(
        dir, "render " +
                 quoted(edited_scene(
                     dir, "acetate.bloom", [](json&) {}, "scene.json")) +
                 " -o flag.png --preset global.acetate.bloom=low --param global.0.threshold=0.4 "
                 "--allow-unvalidated");
    expect_success(run);
    EXPECT_EQ(test::read_file(dir / "flag.png"), test::read_file(dir / "edited.png"));
}

TEST(CliParams, ABadFlagIsOneLineAndWritesNothing) {
    const fs::path dir = test::scratch_dir();
    const std::string scene = quoted(edited_scene(
        dir, "acetate.lighting", [](json&) {}, "scene.json"));
    for (const auto& [flags, expected, code] :
         std::vector<std::tuple<std::string, std::string, int>>{
             {"--param quay.acetate.lighting.day", "expected FLOOR.EFFECT.NAME=VALUE", 2},
             {"--param day=1", "expected FLOOR.EFFECT.NAME=VALUE", 2},
             {"--param quay.acetate.lighting.day=nan", "must be a finite number", 2},
             {"--param quay.acetate.lighting.day=1,2,3,4", "a value has 1, 2 or 3 numbers", 2},
             {"--preset quay.acetate.lighting", "expected FLOOR.EFFECT=PRESET", 2},
             {"--param roofs.acetate.lighting.day=1", "has no floor \"roofs\"", 1},
             {"--param quay.acetate.water.foam=1", "lists \"acetate.water\" 0 times", 1},
             {"--param quay.3.day=1", "the floor lists 1 effects", 1},
             {"--param quay.acetate.lighting.dusk=1", "floors[0].effects[0].params", 1},
             {"--preset quay.0=dawn", "floors[0].effects[0].preset", 1},
         }) {
        SCOPED_TRACE(flags);
        const CliRun run =
            run_acetate(dir, "render " + scene + " -o out.png --allow-unvalidated " + flags);
        EXPECT_EQ(run.code, code) << run.describe();
        expect_refused_after_warnings(run, expected);
        EXPECT_FALSE(fs::exists(dir / "out.png"));
    }
}

}  // namespace
}  // namespace acetate
