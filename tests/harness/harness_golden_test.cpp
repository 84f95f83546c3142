// Golden references (docs/harness.md, "Golden references"): `bless` stores the reference
// cases' outputs as half-float EXR with a manifest bound to the source digest; `validate`
// compares every later build with them under idiff-style gates. The battery's wrong_colour (the
// well_behaved tint turned the wrong way, alpha kept) passes every contract check and fails
// only `golden` against references blessed from the correct tint; references blessed for
// another source fail the run with one line saying to review and bless; unusable references
// are one line naming the file.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "scene/image_io.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;

namespace fs = std::filesystem;
using nlohmann::json;
using test::shell_quote;

class HarnessGolden : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        references_ = dir_ / "references";
    }

    test::CommandResult harness(const std::string& args) const {
        return test::run_command(
            "cd " + shell_quote(dir_.string()) + " && " + test::harness_environment() + " " +
                shell_quote(ACETATE_HARNESS_PATH) + " --registry " +
                shell_quote((dir_ / "registry.json").string()) + " --references " +
                shell_quote(references_.string()) + " " + args,
            dir_);
    }
    static fs::path plugin(const std::string& stem) {
        return fs::path(ACETATE_HARNESS_PLUGIN_DIR) / (stem + ".so");
    }
    // The alpha stage at strictness 1, nothing recorded (no review), its report in report-NAME.
    test::CommandResult validate(const std::string& stem) const {
        return harness("validate " + shell_quote(plugin(stem).string()) +
                       " --stage alpha-tested --strictness 1 --jobs 2 --timeout 60 "
                       "--no-signoffs --report " +
                       shell_quote((dir_ / ("report-" + stem)).string()));
    }
    json report(const std::string& stem) const {
        return json::parse(test::read_file(dir_ / ("report-" + stem) / "report.json"));
    }
    fs::path manifest(const std::string& id) const { return references_ / id / "manifest.json"; }
    json read_manifest(const std::string& id) const {
        return json::parse(test::read_file(manifest(id)));
    }

    // Blesses well_behaved (the correct tint) into the test's references.
    void bless_control() const {
        const test::CommandResult run =
            harness("bless " + shell_quote(plugin("well_behaved").string()) +
                    " --by rita@example.org --report " + shell_quote((dir_ / "bless").string()));
        ASSERT_EQ(run.code, 0) << run.describe();
        EXPECT_TRUE(contains(run.out, "4 reference images blessed by rita@example.org")) << run.out;
    }

    fs::path dir_, references_;
};

// The checks of every case in a report with the given verdict, by name.
std::set<std::string> checks_with(const json& report, const std::string& verdict) {
    std::set<std::string> names;
    for (const json& c : report["cases"])
        for (const json& check : c["checks"])
            if (check["verdict"] == verdict) names.insert(check["check"].get<std::string>());
    return names;
}

TEST_F(HarnessGolden, BlessedReferencesPassTheirOwnPluginAndCatchAWrongColour) {
    bless_control();
    const json m = read_manifest("test.harness.well_behaved");
    EXPECT_EQ(m["format"], "acetate-references/1");
    EXPECT_EQ(m["blessed_by"], "rita@example.org");
    ASSERT_EQ(m["images"].size(), 4u) << m.dump(2);  // defaults at 0 and 2.5 s, low, high
    for (const auto& [id, name] : m["images"].items()) {
        auto image = load_image(references_ / "test.harness.well_behaved" / name.get<std::string>(),
                                ImageRole::Colour);
        ASSERT_TRUE(image) << image.error().message;
        EXPECT_EQ(image->width, 128u);
        EXPECT_EQ(image->height, 80u);
    }

    // The control against its own references: every golden check passes.
    {
        const test::CommandResult run = validate("well_behaved");
        EXPECT_EQ(run.code, 0) << run.describe();
        const json r = report("well_behaved");
        size_t golden = 0;
        for (const json& c : r["cases"])
            for (const json& check : c["checks"])
                if (check["check"] == "golden") {
                    ++golden;
                    EXPECT_EQ(check["verdict"], "PASS") << check.dump(2);
                    EXPECT_TRUE(
                        contains(check["message"].get<std::string>(), "max 0 half-float roundings"))
                        << check.dump(2);
                }
        EXPECT_EQ(golden, 4u);
    }

    // wrong_colour judged against the correct tint's images, as if they had been blessed for
    // its source: golden fails, and nothing else does.
    {
        const fs::path wrong = references_ / "test.harness.wrong_colour";
        fs::copy(references_ / "test.harness.well_behaved", wrong);
        const test::CommandResult described =
            harness("describe " + shell_quote(plugin("wrong_colour").string()) + " --out " +
                    shell_quote((dir_ / "wrong.json").string()));
        ASSERT_EQ(described.code, 0) << described.describe();
        const json info = json::parse(test::read_file(dir_ / "wrong.json"));
        json m2 = read_manifest("test.harness.well_behaved");
        m2["plugin"] = "test.harness.wrong_colour";
        m2["source_digest"] = info["source_digest"];
        test::write_text(wrong / "manifest.json", m2.dump(2));

        const test::CommandResult run = validate("wrong_colour");
        EXPECT_EQ(run.code, 1) << run.describe();
        const json r = report("wrong_colour");
        EXPECT_EQ(checks_with(r, "FAIL"), std::set<std::string>{"golden"}) << run.out;
        EXPECT_TRUE(checks_with(r, "CRASH").empty());
        EXPECT_TRUE(checks_with(r, "TIMEOUT").empty());
        EXPECT_TRUE(checks_with(r, "PASS").count("premultiplied"));
        EXPECT_TRUE(checks_with(r, "PASS").count("coverage"));
        for (const json& c : r["cases"])
            for (const json& check : c["checks"])
                if (check["check"] == "golden") {
                    EXPECT_EQ(check["verdict"], "FAIL") << check.dump(2);
                    EXPECT_TRUE(check["images"].contains("heatmap.composite")) << check.dump(2);
                }
    }
}

TEST_F(HarnessGolden, ReferencesForAnotherSourceFailWithOneLineSayingToBless) {
    bless_control();
    json m = read_manifest("test.harness.well_behaved");
    m["source_digest"] = std::string(64, 'f');
    test::write_text(manifest("test.harness.well_behaved"), m.dump(2));
    const test::CommandResult run = validate("well_behaved");
    EXPECT_EQ(run.code, 1) << run.describe();
    bool named = false;
    const json r = report("well_behaved");
    for (const json& c : r["cases"])
        if (c["id"] == "reference/current") {
            EXPECT_EQ(c["verdict"], "FAIL");
            const std::string message = c["message"].get<std::string>();
            named = contains(message, "were blessed for source ffffffffffff") &&
                    contains(message, "review the new images") &&
                    contains(message, "acetate-harness bless " + plugin("well_behaved").string());
            EXPECT_TRUE(named) << message;
        }
    EXPECT_TRUE(named);
}

TEST_F(HarnessGolden, UnusableReferencesAreOneLineNamingTheFile) {
    bless_control();
    const std::string id = "test.harness.well_behaved";
    const std::string good = test::read_file(manifest(id));

    // A manifest cut short: the run stops before any case, naming the file.
    test::write_text(manifest(id), good.substr(0, good.size() / 2));
    test::CommandResult run = validate("well_behaved");
    EXPECT_EQ(run.code, 1) << run.describe();
    auto lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    EXPECT_TRUE(contains(lines[0], manifest(id).string())) << lines[0];

    // An image it names is missing.
    json m = json::parse(good);
    const std::string first = m["images"].begin().value().get<std::string>();
    test::write_text(manifest(id), good);
    fs::rename(references_ / id / first, dir_ / "moved.exr");
    run = validate("well_behaved");
    EXPECT_EQ(run.code, 1) << run.describe();
    lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    EXPECT_TRUE(contains(lines[0], (references_ / id / first).string() + " is missing"))
        << lines[0];

    // An image of the wrong size: that case's golden check fails, naming the file.
    ImageRGBA small(16, 16);
    ASSERT_TRUE(save_image(references_ / id / first, small));
    run = validate("well_behaved");
    EXPECT_EQ(run.code, 1) << run.describe();
    bool named = false;
    const json r = report("well_behaved");
    for (const json& c : r["cases"])
        for (const json& check : c["checks"])
            if (check["check"] == "golden" && check["verdict"] == "FAIL")
                named = contains(check["message"].get<std::string>(),
                                 "the reference is 16x16, the case renders 128x80");
    EXPECT_TRUE(named);
}

}  // namespace
}  // namespace acetate

namespace acetate {
namespace {

// A plugin's own reference scene (references/<id>/scenes/NAME.json): blessed and judged beside
// the shared scene, rendered as written; editing an image it names makes the references stale
// in one line; a scene that uses another plugin is refused in one line naming the field.
TEST_F(HarnessGolden, APluginsOwnSceneIsBlessedJudgedAndStaleOnceEdited) {
    const std::string id = "test.harness.well_behaved";
    const fs::path scenes = references_ / id / "scenes";
    fs::create_directories(scenes);
    ImageRGBA tile(48, 32);
    for (uint32_t y = 0; y < tile.height; ++y)
        for (uint32_t x = 0; x < tile.width; ++x) {
            float* p = &tile.pixels[(size_t(y) * tile.width + x) * 4];
            const float a = x < 40 ? 1.0f : 0.5f;  // part of it half covered
            p[0] = a * float(x) / 48.0f;
            p[1] = a * float(y) / 32.0f;
            p[2] = a * 0.25f;
            p[3] = a;
        }
    ASSERT_TRUE(save_image(scenes / "pond.exr", tile));
    const json scene = {
        {"format", "acetate-scene/1"},
        {"canvas", {{"width", 64}, {"height", 40}, {"background", {0.1, 0.1, 0.1, 1.0}}}},
        {"floors",
         {{{"name", "pond"},
           {"tiles", {{{"image", "pond.exr"}, {"rect", {8, 4, 48, 32}}}}},
           {"effects", {{{"plugin", id}}}}}}}};
    test::write_text(scenes / "pond.json", scene.dump(2));

    test::CommandResult run =
        harness("bless " + shell_quote(plugin("well_behaved").string()) +
                " --by rita@example.org --report " + shell_quote((dir_ / "bless").string()));
    ASSERT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(contains(run.out, "6 reference images blessed")) << run.out;
    const json m = read_manifest(id);
    ASSERT_TRUE(m["images"].contains("reference/scene-pond/t0")) << m.dump(2);
    ASSERT_TRUE(m["images"].contains("reference/scene-pond/t2.5")) << m.dump(2);
    ASSERT_TRUE(m["scenes"].contains("pond")) << m.dump(2);
    auto image =
        load_image(references_ / id / m["images"]["reference/scene-pond/t0"].get<std::string>(),
                   ImageRole::Colour);
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_EQ(image->width, 64u);  // the scene's canvas, not the shared scene's
    EXPECT_EQ(image->height, 40u);

    // Judged as blessed: both scene cases compare their image and pass.
    run = validate("well_behaved");
    EXPECT_EQ(run.code, 0) << run.describe();
    size_t scene_cases = 0;
    const json judged = report("well_behaved");  // named: a loop over a temporary's member dangles
    for (const json& c : judged["cases"])
        if (c["id"].get<std::string>().rfind("reference/scene-pond/", 0) == 0) {
            ++scene_cases;
            EXPECT_EQ(c["verdict"], "PASS") << c.dump(2);
        }
    EXPECT_EQ(scene_cases, 2u) << run.out;

    // An image the scene names is edited: the references are stale, in one line naming it.
    tile.pixels[0] = 0.75f;
    ASSERT_TRUE(save_image(scenes / "pond.exr", tile));
    run = validate("well_behaved");
    EXPECT_EQ(run.code, 1) << run.describe();
    bool stale = false;
    const json stale_report = report("well_behaved");
    for (const json& c : stale_report["cases"])
        if (c["id"] == "reference/current") {
            const std::string message = c["message"].get<std::string>();
            stale = contains(message, (scenes / "pond.json").string()) &&
                    contains(message, "an image it names changed") &&
                    contains(message, "acetate-harness bless");
            EXPECT_TRUE(stale) << message;
        }
    EXPECT_TRUE(stale);

    // A reference scene that uses another plugin: refused before any case, naming the field.
    json other = scene;
    other["floors"][0]["effects"][0]["plugin"] = "acetate.water";
    test::write_text(scenes / "pond.json", other.dump(2));
    run = validate("well_behaved");
    EXPECT_EQ(run.code, 1) << run.describe();
    const auto lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    EXPECT_TRUE(contains(lines[0], (scenes / "pond.json").string() +
                                       ": floors[0].effects[0].plugin: \"acetate.water\" is not"))
        << lines[0];
}

}  // namespace
}  // namespace acetate
