// `acetate check-shaders`, which acetate_add_effect runs on every plugin it builds: an error in
// the pass only a preset picks is found and named by its shader file and line; a pass whose text
// is no file's is named by its pass; every shipped plugin passes (their builds run it too).
#include "cli_fixtures.hpp"

namespace acetate {
namespace {

using namespace cli_test;

TEST(CheckShaders, AnErrorInAPresetsPassNamesTheShaderFileAndLine) {
    const fs::path dir = test::scratch_dir();
    const fs::path source = fs::path(ACETATE_SOURCE_DIR) / "tests/plugins/preset_shader_error";
    const fs::path plugin = fs::path(ACETATE_TEST_PLUGIN_DIR) / "preset_shader_error.so";
    const CliRun run = run_acetate(dir, "check-shaders '" + plugin.string() + "' --shader '" +
                                            (source / "plain.frag").string() + "' --shader '" +
                                            (source / "fancy.frag").string() + "'");
    EXPECT_TRUE(run.exited && run.code == 1) << run.describe();
    const std::vector<std::string> lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 2u) << run.describe();
    // Line 4 of fancy.frag, only under "ultra" (the only preset that picks it).
    EXPECT_EQ(lines[0], (source / "fancy.frag").string() +
                            ":4: error: 'undeclared_gain' : undeclared identifier (pass "
                            "\"floor0.test.preset_shader_error.fancy\", preset \"ultra\")")
        << run.describe();
    EXPECT_EQ(lines[1], "acetate check-shaders: test.preset_shader_error: 1 error");
}

TEST(CheckShaders, APassWhoseTextIsNoFilesIsNamedByItsPass) {
    const fs::path dir = test::scratch_dir();
    const fs::path plugin = fs::path(ACETATE_TEST_PLUGIN_DIR) / "bad_shader.so";
    const CliRun run = run_acetate(dir, "check-shaders '" + plugin.string() + "'");
    EXPECT_TRUE(run.exited && run.code == 1) << run.describe();
    EXPECT_TRUE(test::contains(run.err, plugin.string() +
                                            ": pass \"floor0.test.bad_shader.broken\" "
                                            "(defaults): "))
        << run.describe();
    EXPECT_TRUE(test::contains(run.err, "undeclared_thing")) << run.describe();
}

TEST(CheckShaders, EveryShippedPluginPasses) {
    const fs::path dir = test::scratch_dir();
    for (const char* name : {"lighting", "bloom", "water", "specular", "fire"}) {
        const fs::path plugin = fs::path(ACETATE_PLUGIN_DIR) / (std::string(name) + ".so");
        const CliRun run = run_acetate(dir, "check-shaders '" + plugin.string() + "'");
        expect_success(run);
        EXPECT_TRUE(
            test::contains(run.out, std::string("acetate check-shaders: acetate.") + name + ": "))
            << run.describe();
        EXPECT_EQ(run.err, "") << run.describe();
    }
}

}  // namespace
}  // namespace acetate
