// The shipped plugins against their committed golden references (validation/references/): every
// reference case (the shared scene with the defaults and each preset, and the plugin's own
// scenes) renders and its `golden` check passes, not skips. A shader change that was not
// reviewed and blessed fails here, in the test suite, not only in the demo.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::shell_quote;

class ShippedReferences : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedReferences, EveryReferenceCaseMatchesItsBlessedImage) {
    const fs::path dir = test::scratch_dir();
    const fs::path plugin = fs::path(ACETATE_PLUGIN_DIR) / (GetParam() + ".so");
    const std::string harness =
        "cd " + shell_quote(dir.string()) + " && " + test::harness_environment() + " " +
        shell_quote(ACETATE_HARNESS_PATH) + " --registry " +
        shell_quote((dir / "registry.json").string()) + " --references " +
        shell_quote((fs::path(ACETATE_SOURCE_VALIDATION_DIR) / "references").string()) + " ";

    const test::CommandResult listed = test::run_command(
        harness + "validate " + shell_quote(plugin.string()) + " --list-cases", dir);
    ASSERT_EQ(listed.code, 0) << listed.describe();
    std::string cases;
    size_t planned = 0, own_scenes = 0;
    for (const std::string& id : test::nonempty_lines(listed.out))
        if (id.rfind("reference/", 0) == 0) {
            cases += " --case " + id;
            ++planned;
            own_scenes += id.rfind("reference/scene-", 0) == 0;
        }
    EXPECT_GE(own_scenes, 2u) << "every shipped plugin has a scene of its own at two times";

    const test::CommandResult run = test::run_command(
        harness + "validate " + shell_quote(plugin.string()) + " --no-signoffs --jobs 2" + cases +
            " --report " + shell_quote((dir / "report").string()),
        dir);
    EXPECT_EQ(run.code, 0) << run.describe();
    const json report = json::parse(test::read_file(dir / "report" / "report.json"));
    size_t compared = 0;
    for (const json& c : report["cases"])
        for (const json& check : c["checks"])
            if (check["check"] == "golden") {
                ++compared;
                EXPECT_EQ(check["verdict"], "PASS") << c["id"] << ": " << check["message"];
            }
    EXPECT_EQ(compared, planned);
}

INSTANTIATE_TEST_SUITE_P(Shipped, ShippedReferences,
                         ::testing::Values("lighting", "bloom", "water", "specular", "fire"));

}  // namespace
}  // namespace acetate
