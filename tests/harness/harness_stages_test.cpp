// Validation stages through the `acetate-harness` CLI (docs/registry.md): review, validate,
// promote and status on a private registry, and `acetate render` loading only what that
// registry holds VALIDATED for the exact binary.
//
// The plugin is a copy of the well_behaved control in a private folder; a rebuilt binary is
// simulated by appending one byte to the copy (still loadable, another SHA-256, the same
// source digest). Every validate runs at strictness 1 with two jobs; the runs that need no
// integration stop at ALPHA_TESTED.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "registry.hpp"
#include "scene/image_io.hpp"
#include "test_files.hpp"
#include "test_signer.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;

namespace fs = std::filesystem;
using nlohmann::json;
using test::CommandResult;
using test::shell_quote;

constexpr const char* kId = "test.harness.well_behaved";
constexpr const char* kVersion = "1.0.0";
// Seconds a case may take: a case needs 1 to 5 s here, more when the machine is busy.
constexpr int kTimeoutSeconds = 30;

json parse_json(const std::string& text, const std::string& what) {
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        ADD_FAILURE() << what << ": " << e.what() << "\n" << text;
        return json::object();
    }
}

class HarnessStages : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        plugins_ = dir_ / "plugins";
        fs::create_directories(plugins_);
        const fs::path built = fs::path(ACETATE_HARNESS_PLUGIN_DIR) / "well_behaved.so";
        ASSERT_TRUE(fs::is_regular_file(built)) << built;
        fs::copy_file(built, plugin());
        registry_ = dir_ / "registry.json";
    }

    fs::path plugin() const { return plugins_ / "well_behaved.so"; }

    // `acetate-harness --registry REGISTRY ARGS` in the test folder.
    CommandResult harness(const std::string& args, const fs::path& registry) const {
        return test::run_command(
            "cd " + shell_quote(dir_.string()) + " && " + test::harness_environment() + " " +
                test::signer_environment() + " " + shell_quote(ACETATE_HARNESS_PATH) +
                " --registry " + shell_quote(registry.string()) + " " + args,
            dir_);
    }
    CommandResult harness(const std::string& args) const { return harness(args, registry_); }

    // `validate PLUGIN` with the flags every run here uses, the report in `report`.
    CommandResult validate(const fs::path& plugin, const fs::path& registry, const fs::path& report,
                           const std::string& extra = "") const {
        return harness("validate " + shell_quote(plugin.string()) + " --report " +
                           shell_quote(report.string()) + " --strictness 1 --jobs 2 --timeout " +
                           std::to_string(kTimeoutSeconds) + " " + extra,
                       registry);
    }

    CommandResult review(const fs::path& plugin, const fs::path& registry) const {
        return harness("review " + shell_quote(plugin.string()) +
                           " --reviewer rita@example.org --notes 'read the tint shader'",
                       registry);
    }

    // `status --json`: the registry with each entry's stage.
    json status(const fs::path& registry) const {
        const CommandResult run = harness("status --json", registry);
        EXPECT_EQ(run.code, 0) << run.describe();
        return parse_json(run.out, "status --json");
    }
    // The entry of `id` in `status --json`; null when there is none.
    json entry(const fs::path& registry, const std::string& id = kId) const {
        const json s = status(registry);
        if (s.contains("plugins"))
            for (const json& e : s["plugins"])
                if (e["id"] == id) return e;
        return nullptr;
    }
    std::string stage(const fs::path& registry, const std::string& id = kId) const {
        const json e = entry(registry, id);
        return e.is_null() ? "UNVALIDATED" : e["stage"].get<std::string>();
    }

    // What the plugin declares, from `acetate-harness describe`.
    json describe(const fs::path& plugin) const {
        const fs::path out = dir_ / "describe.json";
        const CommandResult run = harness("describe " + shell_quote(plugin.string()) + " --out " +
                                          shell_quote(out.string()));
        EXPECT_EQ(run.code, 0) << run.describe();
        return parse_json(test::read_file(out), out.string());
    }

    // A 16x16 scene with one floor carrying the plugin under test.
    fs::path write_scene() const {
        ImageRGBA tile(16, 16);
        for (size_t i = 0; i < tile.pixels.size(); ++i) tile.pixels[i] = (i % 4 == 3) ? 1.0f : 0.4f;
        test::write_exr(dir_ / "tile.exr", tile);
        return test::write_text(dir_ / "scene.json", R"({"format": "acetate-scene/1",
  "canvas": {"width": 16, "height": 16},
  "floors": [{"name": "ground", "tiles": [{"image": "tile.exr", "rect": [0, 0, 16, 16]}],
              "effects": [{"plugin": "test.harness.well_behaved", "params": {"gain": 1.2}}]}]}
)");
    }

    // `acetate render scene.json -o OUT --plugin-path <the copy's folder> --registry REGISTRY`.
    CommandResult render(const fs::path& out) const {
        return test::run_command(
            "cd " + shell_quote(dir_.string()) + " && " + test::harness_environment() + " " +
                test::signer_environment() + " " + shell_quote(ACETATE_CLI_PATH) +
                " render scene.json -o " + shell_quote(out.string()) + " --plugin-path " +
                shell_quote(plugins_.string()) + " --registry " + shell_quote(registry_.string()),
            dir_);
    }

    static json report(const fs::path& report_dir) {
        return parse_json(test::read_file(report_dir / "report.json"),
                          (report_dir / "report.json").string());
    }

    fs::path dir_, plugins_, registry_;
};

// UNVALIDATED -> REVIEWED -> INTEGRATED -> VALIDATED, a render; then a rebuilt binary: refused
// by the host until validate has run on it, after which its promotion (bound to the source)
// makes it VALIDATED again.
TEST_F(HarnessStages, ThroughEveryStageToTheHostAndBackAfterARebuild) {
    const std::string old_sha = file_sha256(plugin()).value();

    // Checks pass before any review, but nothing may be recorded.
    {
        SCOPED_TRACE("validate before any review");
        const CommandResult run = validate(plugin(), registry_, dir_ / "report-unreviewed",
                                           "--no-signoffs --stage alpha-tested");
        EXPECT_EQ(run.code, 0) << run.describe();
        EXPECT_TRUE(contains(run.out, "all checks passed")) << run.describe();
        EXPECT_TRUE(contains(run.out, "ALPHA_TESTED: passed, but not recorded")) << run.describe();
        EXPECT_TRUE(contains(run.out, "needs REVIEWED first")) << run.describe();
        EXPECT_TRUE(contains(run.out, "acetate-harness review " + plugin().string()))
            << run.describe();
        const json r = report(dir_ / "report-unreviewed");
        EXPECT_EQ(r["stage_before"], "UNVALIDATED");
        EXPECT_EQ(r["stage_after"], "UNVALIDATED");
        ASSERT_EQ(r["stages"].size(), 1u);
        EXPECT_EQ(r["stages"][0]["passed"], true);
        EXPECT_EQ(r["stages"][0]["recorded"], false);
        auto registry = Registry::load(registry_);
        ASSERT_TRUE(registry) << registry.error().message;
        EXPECT_EQ(registry->effective_stage(kId, kVersion, old_sha,
                                            r["source_digest"].get<std::string>()),
                  ValidationStage::Unvalidated);
        EXPECT_EQ(registry->find(kId, kVersion), nullptr);
        EXPECT_EQ(stage(registry_), "UNVALIDATED");
    }

    // A promotion needs INTEGRATED: refused at UNVALIDATED, and at REVIEWED.
    {
        SCOPED_TRACE("promote too early");
        CommandResult run =
            harness("promote " + shell_quote(plugin().string()) + " --by pat@example.org");
        EXPECT_EQ(run.code, 1) << run.describe();
        auto lines = test::nonempty_lines(run.err);
        ASSERT_EQ(lines.size(), 1u) << run.describe();
        EXPECT_TRUE(contains(lines[0], kId)) << lines[0];
        EXPECT_TRUE(contains(lines[0], "is UNVALIDATED, not INTEGRATED")) << lines[0];
        EXPECT_EQ(stage(registry_), "UNVALIDATED");

        run = review(plugin(), registry_);
        EXPECT_EQ(run.code, 0) << run.describe();
        EXPECT_TRUE(contains(run.out, "now REVIEWED")) << run.describe();
        const json e = entry(registry_);
        ASSERT_FALSE(e.is_null());
        EXPECT_EQ(e["stage"], "REVIEWED");
        EXPECT_EQ(e["review"]["by"], "rita@example.org");
        EXPECT_EQ(e["review"]["notes"], "read the tint shader");
        EXPECT_EQ(e["binary_sha256"], old_sha);

        run = harness("promote " + shell_quote(plugin().string()) + " --by pat@example.org");
        EXPECT_EQ(run.code, 1) << run.describe();
        lines = test::nonempty_lines(run.err);
        ASSERT_EQ(lines.size(), 1u) << run.describe();
        EXPECT_TRUE(contains(lines[0], kId)) << lines[0];
        EXPECT_TRUE(contains(lines[0], "is REVIEWED, not INTEGRATED")) << lines[0];
        EXPECT_EQ(stage(registry_), "REVIEWED");
    }

    // validate (up to INTEGRATED by default), then promote.
    {
        SCOPED_TRACE("validate and promote");
        const CommandResult run = validate(plugin(), registry_, dir_ / "report-1", "--no-signoffs");
        EXPECT_EQ(run.code, 0) << run.describe();
        EXPECT_TRUE(contains(run.out, "REVIEWED -> INTEGRATED")) << run.describe();
        const json r = report(dir_ / "report-1");
        ASSERT_EQ(r["stages"].size(), 2u) << r["stages"].dump(2);
        EXPECT_EQ(r["stages"][0]["stage"], "ALPHA_TESTED");
        EXPECT_EQ(r["stages"][0]["recorded"], true);
        EXPECT_EQ(r["stages"][1]["stage"], "INTEGRATED");
        EXPECT_EQ(r["stages"][1]["recorded"], true);
        const json e = entry(registry_);
        ASSERT_FALSE(e.is_null());
        EXPECT_EQ(e["stage"], "INTEGRATED");
        EXPECT_EQ(e["integrated"]["binary_sha256"], old_sha);

        // Evidence at strictness 1, below the default: promotion refuses it until a waiver
        // says why, and shows it either way.
        const std::string promote_command = "promote " + shell_quote(plugin().string()) +
                                            " --by pat@example.org --notes "
                                            "'evidence read'";
        const CommandResult refused = harness(promote_command);
        EXPECT_EQ(refused.code, 1) << refused.describe();
        EXPECT_TRUE(contains(refused.out, "evidence at strictness 1, below the default 5"))
            << refused.describe();
        const auto lines = test::nonempty_lines(refused.err);
        ASSERT_EQ(lines.size(), 1u) << refused.describe();
        EXPECT_TRUE(contains(lines[0],
                             "promotion refused: its evidence was taken at strictness "
                             "1, below the default 5"))
            << lines[0];
        EXPECT_EQ(entry(registry_)["stage"], "INTEGRATED");
        const CommandResult waived =
            harness("waive " + shell_quote(plugin().string()) +
                    " strictness --reason 'a test: strictness 1 keeps it under a minute' "
                    "--until 2099-12-31 --by pat@example.org");
        EXPECT_EQ(waived.code, 0) << waived.describe();

        const CommandResult promote = harness(promote_command);
        EXPECT_TRUE(contains(promote.out, "waiver: strictness until 2099-12-31"))
            << promote.describe();
        EXPECT_EQ(promote.code, 0) << promote.describe();
        EXPECT_TRUE(contains(promote.out, "promoted to VALIDATED")) << promote.describe();
        const json after = entry(registry_);
        EXPECT_EQ(after["stage"], "VALIDATED");
        EXPECT_EQ(after["promotion"]["by"], "pat@example.org");
        const std::string markdown = test::read_file(dir_ / "VALIDATION-REGISTRY.md");
        EXPECT_TRUE(contains(markdown, kId)) << markdown;
        EXPECT_TRUE(contains(markdown, "VALIDATED")) << markdown;
        EXPECT_TRUE(contains(markdown, "pat@example.org")) << markdown;
    }

    // The host loads the validated copy.
    write_scene();
    {
        SCOPED_TRACE("render the validated binary");
        const CommandResult run = render(dir_ / "validated.png");
        EXPECT_EQ(run.code, 0) << run.describe();
        EXPECT_TRUE(run.err.empty()) << run.describe();
        EXPECT_TRUE(fs::is_regular_file(dir_ / "validated.png")) << run.describe();
    }

    // "Rebuild": one byte more. The registry still holds the old binary; the host refuses this one.
    { std::ofstream(plugin(), std::ios::binary | std::ios::app).put('\0'); }
    const std::string new_sha = file_sha256(plugin()).value();
    ASSERT_NE(new_sha, old_sha);
    {
        SCOPED_TRACE("after the rebuild");
        const CommandResult listed = harness("status");
        EXPECT_EQ(listed.code, 0) << listed.describe();
        EXPECT_TRUE(contains(listed.out, kId)) << listed.describe();
        EXPECT_TRUE(contains(listed.out, old_sha.substr(0, 12))) << listed.describe();
        EXPECT_FALSE(contains(listed.out, new_sha.substr(0, 12))) << listed.describe();
        const json e = entry(registry_);
        EXPECT_EQ(e["binary_sha256"], old_sha);
        EXPECT_EQ(e["stage"], "VALIDATED");

        const CommandResult run = render(dir_ / "rebuilt.png");
        EXPECT_EQ(run.code, 1) << run.describe();
        const auto lines = test::nonempty_lines(run.err);
        ASSERT_EQ(lines.size(), 1u) << run.describe();
        EXPECT_TRUE(contains(lines[0], "not VALIDATED")) << lines[0];
        EXPECT_TRUE(contains(lines[0], plugin().string())) << lines[0];
        EXPECT_TRUE(contains(lines[0], new_sha.substr(0, 12))) << lines[0];
        EXPECT_FALSE(fs::exists(dir_ / "rebuilt.png"));
    }

    // validate the new binary: INTEGRATED evidence for it, and the promotion still holds.
    {
        SCOPED_TRACE("validate the rebuilt binary");
        const CommandResult run = validate(plugin(), registry_, dir_ / "report-2", "--no-signoffs");
        EXPECT_EQ(run.code, 0) << run.describe();
        const json r = report(dir_ / "report-2");
        EXPECT_EQ(r["binary_sha256"], new_sha);
        EXPECT_EQ(r["stage_before"], "REVIEWED");
        EXPECT_EQ(r["stage_after"], "VALIDATED");
        const json e = entry(registry_);
        ASSERT_FALSE(e.is_null());
        EXPECT_EQ(e["stage"], "VALIDATED");
        EXPECT_EQ(e["binary_sha256"], new_sha);
        EXPECT_EQ(e["alpha_tested"]["binary_sha256"], new_sha);
        EXPECT_EQ(e["integrated"]["binary_sha256"], new_sha);
        EXPECT_EQ(e["promotion"]["by"], "pat@example.org");

        const CommandResult again = render(dir_ / "rebuilt.png");
        EXPECT_EQ(again.code, 0) << again.describe();
        EXPECT_TRUE(again.err.empty()) << again.describe();
        EXPECT_TRUE(fs::is_regular_file(dir_ / "rebuilt.png")) << again.describe();
    }
}

// Committed sign-offs (the acetate-registry/1 format, as validation/signoffs.json): on a fresh
// registry, validate imports the review, runs both automated stages and then imports the
// promotion: UNVALIDATED straight through to VALIDATED. The sign-offs were written for
// another binary of the same source (a maintainer's build), which does not matter: sign-offs
// bind to the source digest.
TEST_F(HarnessStages, CommittedSignOffsTakeAFreshRegistryToValidated) {
    const json info = describe(plugin());
    ASSERT_EQ(info["id"], kId);
    const std::string source = info["source_digest"].get<std::string>();
    ASSERT_EQ(source.size(), 64u) << "the plugin was built without a source digest";
    const std::string other_binary(64, 'a');
    ASSERT_NE(info["binary_sha256"], other_binary);
    // Signed as a maintainer signs with review and promote.
    const std::string version = info["version"].get<std::string>();
    SignOff review{"maintainers@example.org", "2026-01-02T03:04:05Z", "committed", source, ""};
    test::sign(review, kId, version, ValidationStage::Reviewed);
    SignOff promoted{"maintainers@example.org", "2026-01-02T03:05:06Z", "committed", source, ""};
    test::sign(promoted, kId, version, ValidationStage::Validated);
    auto as_json = [](const SignOff& s) {
        return json{{"by", s.by},
                    {"at", s.at},
                    {"notes", s.notes},
                    {"source_digest", s.source_digest},
                    {"signature", s.signature}};
    };
    const json signoff = as_json(review);
    const json promotion = as_json(promoted);
    const json file = {{"format", "acetate-registry/1"},
                       {"plugins",
                        {{{"id", kId},
                          {"version", info["version"]},
                          {"stage", "REVIEWED"},
                          {"binary_sha256", other_binary},
                          {"source_digest", source},
                          {"review", signoff},
                          {"promotion", promotion}}}}};
    const fs::path signoffs = test::write_text(dir_ / "signoffs.json", file.dump(2));
    auto parsed = Registry::load(signoffs);
    ASSERT_TRUE(parsed) << parsed.error().message;

    EXPECT_EQ(stage(registry_), "UNVALIDATED");
    const std::string with_signoffs = "--signoffs " + shell_quote(signoffs.string());
    // At strictness 1 the review is imported and the stages recorded, but not the promotion:
    // evidence below the default strictness is promoted only under a waiver.
    CommandResult run = validate(plugin(), registry_, dir_ / "report", with_signoffs);
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(contains(run.out, "imported the committed review by maintainers@example.org"))
        << run.describe();
    EXPECT_TRUE(contains(run.out, "not imported from " + signoffs.string() +
                                      ": the promotion by maintainers@example.org: " + kId + " " +
                                      version +
                                      ": promotion refused: its evidence was taken at "
                                      "strictness 1"))
        << run.describe();
    EXPECT_EQ(stage(registry_), "INTEGRATED");
    run = harness("waive " + shell_quote(plugin().string()) +
                  " strictness --reason 'a test at strictness 1' --until 2099-12-31 --by "
                  "maintainers@example.org");
    EXPECT_EQ(run.code, 0) << run.describe();
    run = validate(plugin(), registry_, dir_ / "report", with_signoffs);
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(contains(run.out, "imported the committed promotion by maintainers@example.org"))
        << run.describe();
    EXPECT_TRUE(contains(run.out, "-> VALIDATED")) << run.describe();
    const json e = entry(registry_);
    ASSERT_FALSE(e.is_null());
    EXPECT_EQ(e["stage"], "VALIDATED");
    EXPECT_EQ(e["binary_sha256"], info["binary_sha256"]);
    EXPECT_EQ(e["review"]["at"], "2026-01-02T03:04:05Z");
    EXPECT_EQ(e["promotion"]["at"], "2026-01-02T03:05:06Z");
    EXPECT_EQ(e["integrated"]["binary_sha256"], info["binary_sha256"]);
}

// A coverage-preserving global effect reaches VALIDATED with bloom, a coverage-expanding global
// effect, INTEGRATED beside it: the integration stack runs bloom first and judges the effect
// under test on its own input and output (the composite bloom left, whose alpha bloom grew),
// not from the composite before every global effect to after all of them.
TEST_F(HarnessStages, APreservingGlobalEffectIsValidatedAfterBloom) {
    for (const fs::path& built : {fs::path(ACETATE_PLUGIN_DIR) / "bloom.so",
                                  fs::path(ACETATE_HARNESS_PLUGIN_DIR) / "global_grade.so"}) {
        ASSERT_TRUE(fs::is_regular_file(built)) << built;
        fs::copy_file(built, plugins_ / built.filename());
    }
    const std::string paths = "--no-signoffs --plugin-path " + shell_quote(plugins_.string());
    const fs::path bloom = plugins_ / "bloom.so", grade = plugins_ / "global_grade.so";
    for (const fs::path& plugin : {bloom, grade}) {
        const CommandResult reviewed = review(plugin, registry_);
        EXPECT_EQ(reviewed.code, 0) << reviewed.describe();
    }
    CommandResult run = validate(bloom, registry_, dir_ / "report-bloom", paths);
    ASSERT_EQ(run.code, 0) << run.describe();
    ASSERT_EQ(stage(registry_, "acetate.bloom"), "INTEGRATED") << run.describe();

    run = validate(grade, registry_, dir_ / "report-grade", paths);
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(contains(run.out, "integration: with 1 other integrated plugin")) << run.out;
    EXPECT_EQ(stage(registry_, "test.harness.global_grade"), "INTEGRATED");
    const json r = report(dir_ / "report-grade");
    bool judged = false;
    for (const json& c : r["cases"]) {
        if (c["id"] != "integration/stack") continue;
        for (const json& check : c["checks"])
            if (check["check"] == "coverage") {
                judged = true;
                EXPECT_EQ(check["verdict"], "PASS") << check.dump(2);
            }
    }
    EXPECT_TRUE(judged) << "no coverage check in integration/stack";

    run = harness("waive " + shell_quote(grade.string()) +
                  " strictness --reason 'a test at strictness 1' --until 2099-12-31 --by "
                  "pat@example.org");
    EXPECT_EQ(run.code, 0) << run.describe();
    run = harness("promote " + shell_quote(grade.string()) +
                  " --by pat@example.org --notes 'evidence read'");
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_EQ(stage(registry_, "test.harness.global_grade"), "VALIDATED");
}

// Two validates at once on one registry, each up to ALPHA_TESTED only: the registry's lock
// makes them take turns, so both records survive, and neither goes past ALPHA_TESTED.
TEST_F(HarnessStages, AlphaTestedOnlyAndTwoRunsShareOneRegistry) {
    const fs::path glow = fs::path(ACETATE_HARNESS_PLUGIN_DIR) / "expanding_glow.so";
    ASSERT_TRUE(fs::is_regular_file(glow)) << glow;
    for (const fs::path& p : {plugin(), glow}) {
        const CommandResult run = review(p, registry_);
        ASSERT_EQ(run.code, 0) << run.describe();
    }
    EXPECT_EQ(stage(registry_), "REVIEWED");
    EXPECT_EQ(stage(registry_, "test.harness.expanding_glow"), "REVIEWED");

    CommandResult runs[2];
    const fs::path plugins[2] = {plugin(), glow};
    std::vector<std::thread> threads;
    for (int i = 0; i < 2; ++i)
        threads.emplace_back([&, i] {
            runs[i] = validate(plugins[i], registry_, dir_ / ("report-" + std::to_string(i)),
                               "--no-signoffs --stage alpha-tested");
        });
    for (std::thread& t : threads) t.join();
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(runs[i].code, 0) << runs[i].describe();
        EXPECT_TRUE(contains(runs[i].out, "REVIEWED -> ALPHA_TESTED")) << runs[i].describe();
        const json r = report(dir_ / ("report-" + std::to_string(i)));
        ASSERT_EQ(r["stages"].size(), 1u) << r["stages"].dump(2);
        EXPECT_EQ(r["stages"][0]["stage"], "ALPHA_TESTED");
        EXPECT_EQ(r["stages"][0]["recorded"], true);
    }

    auto registry = Registry::load(registry_);
    ASSERT_TRUE(registry) << registry.error().message;
    ASSERT_EQ(registry->entries().size(), 2u);
    for (const RegistryEntry& e : registry->entries()) {
        EXPECT_EQ(e.stage(), ValidationStage::AlphaTested) << e.id;
        EXPECT_TRUE(e.review) << e.id;
        EXPECT_TRUE(e.alpha_tested) << e.id;
        EXPECT_FALSE(e.integrated) << e.id;
        EXPECT_FALSE(e.promotion) << e.id;
    }
    EXPECT_EQ(stage(registry_), "ALPHA_TESTED");
    EXPECT_EQ(stage(registry_, "test.harness.expanding_glow"), "ALPHA_TESTED");
    const std::string markdown = test::read_file(dir_ / "VALIDATION-REGISTRY.md");
    EXPECT_TRUE(contains(markdown, kId)) << markdown;
    EXPECT_TRUE(contains(markdown, "test.harness.expanding_glow")) << markdown;
}

// Bad input: one line, a non-zero status, nothing recorded.
TEST_F(HarnessStages, BadInputIsOneLine) {
    {
        SCOPED_TRACE("a file that does not exist");
        const fs::path missing = dir_ / "nonexistent.so";
        const CommandResult run =
            validate(missing, registry_, dir_ / "report-missing", "--no-signoffs");
        EXPECT_EQ(run.code, 1) << run.describe();
        const auto lines = test::nonempty_lines(run.err);
        ASSERT_EQ(lines.size(), 1u) << run.describe();
        EXPECT_TRUE(contains(lines[0], missing.string())) << lines[0];
    }
    {
        SCOPED_TRACE("a file that is not a plugin");
        const fs::path junk = test::write_text(dir_ / "junk.so", "not a shared library\n");
        const CommandResult run = validate(junk, registry_, dir_ / "report-junk", "--no-signoffs");
        EXPECT_EQ(run.code, 1) << run.describe();
        const auto lines = test::nonempty_lines(run.err);
        ASSERT_EQ(lines.size(), 1u) << run.describe();
        EXPECT_TRUE(contains(lines[0], junk.string())) << lines[0];
        // The loader's own reason, not nested in the describe child's failure nor dlopen's
        // wrapping ("invalid ELF header): Bad file descriptor").
        EXPECT_TRUE(contains(lines[0], junk.string() + ": cannot describe the plugin: not a shared "
                                                       "library (it does not start with an ELF "
                                                       "header)"))
            << lines[0];
        EXPECT_EQ(lines[0].find(junk.string()), lines[0].rfind(junk.string()))
            << "the file is named once: " << lines[0];
        EXPECT_FALSE(contains(lines[0], "Bad file descriptor")) << lines[0];
        const json r = report(dir_ / "report-junk");
        ASSERT_TRUE(r.contains("error")) << r.dump(2);
        EXPECT_FALSE(r["error"].get<std::string>().empty()) << r.dump(2);
        EXPECT_TRUE(contains(r["error"].get<std::string>(), junk.string())) << r.dump(2);
        EXPECT_TRUE(r["cases"].empty());
    }
    {
        SCOPED_TRACE("strictness out of range");
        const CommandResult run = harness(
            "validate " + shell_quote(plugin().string()) + " --no-signoffs --report " +
            shell_quote((dir_ / "report-11").string()) + " --strictness 11 --jobs 2 --timeout 10");
        EXPECT_EQ(run.code, 2) << run.describe();
        EXPECT_FALSE(run.err.empty()) << run.describe();
        EXPECT_FALSE(fs::exists(dir_ / "report-11"));
    }
    EXPECT_FALSE(fs::exists(registry_)) << "bad input recorded something";
}

}  // namespace
}  // namespace acetate
