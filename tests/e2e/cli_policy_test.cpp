// The host load policy of `acetate render` (docs/registry.md, "Host policy"): a plugin is
// loaded only if the validation registry has it VALIDATED for its exact binary (SHA-256);
// anything else is refused with one line before the library is opened, unless
// --allow-unvalidated, which loads it with one warning line. `--registry FILE` or
// ACETATE_REGISTRY pick the registry.
//
// Each test works on its own copy of lighting.so in a private --plugin-path folder, so the
// registry can pin that copy and a test can change its bytes. Whether the copy was opened is
// read from the dynamic linker's own log (LD_DEBUG=files, written to LD_DEBUG_OUTPUT files).

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "acetate/host/host.hpp"
#include "plugins/plugin_loader.hpp"
#include "registry.hpp"
#include "registry_location.hpp"
#include "scene/image_io.hpp"
#include "test_files.hpp"
#include "test_signer.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;

namespace fs = std::filesystem;

struct CliRun {
    int code = -1;  // exit status; -1 when killed by a signal
    std::string out, err;
    std::string ld_log;  // the dynamic linker's LD_DEBUG=files output, every process
    std::string command;

    std::string describe() const {
        return "command: " + command + "\nexit code: " + std::to_string(code) +
               "\n--- stdout ---\n" + out + "--- stderr ---\n" + err;
    }
};

class HostPolicy : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        plugins_ = dir_ / "plugins";
        fs::create_directories(plugins_);
        // The copy the CLI finds first, and a byte-identical one this test process reads the
        // descriptor from (so the file a test later changes was never mapped here).
        const fs::path built = fs::path(ACETATE_PLUGIN_DIR) / "lighting.so";
        ASSERT_TRUE(fs::is_regular_file(built)) << built;
        fs::copy_file(built, plugin_file());
        fs::create_directories(dir_ / "probe");
        fs::copy_file(built, dir_ / "probe" / "lighting.so");

        ImageRGBA tile(16, 16);
        for (size_t i = 0; i < tile.pixels.size(); ++i) tile.pixels[i] = (i % 4 == 3) ? 1.0f : 0.4f;
        test::write_exr(dir_ / "tile.exr", tile);
        test::write_text(dir_ / "scene.json", scene_text(true));
        test::write_text(dir_ / "plain.json", scene_text(false));
    }

    static std::string scene_text(bool with_lighting) {
        const std::string effects =
            with_lighting ? R"([{"plugin": "acetate.lighting", "params": {"day": 0.5}}])" : "[]";
        return R"({"format": "acetate-scene/1", "canvas": {"width": 16, "height": 16},
  "floors": [{"name": "ground", "tiles": [{"image": "tile.exr", "rect": [0, 0, 16, 16]}],
              "lights": [{"pos": [8, 8], "radius": 6, "color": [1, 1, 1], "intensity": 1}],
              "effects": )" +
               effects + "}]}\n";
    }

    fs::path plugin_file() const { return plugins_ / "lighting.so"; }

    // Runs `acetate render ARGS --plugin-path <private copy>` in the test folder; `env` is put
    // before the command (e.g. "ACETATE_REGISTRY='...'").
    CliRun render(const std::string& args, const std::string& env = "") {
        static int counter = 0;
        const std::string n = std::to_string(counter++);
        const fs::path out_file = dir_ / ("stdout-" + n + ".txt");
        const fs::path err_file = dir_ / ("stderr-" + n + ".txt");
        const fs::path ld_dir = dir_ / ("ld-" + n);
        fs::create_directories(ld_dir);
        const fs::path cache = fs::temp_directory_path() / "acetate-policy-test-cache";
        fs::create_directories(cache / "mesa");
        fs::create_directories(cache / "xdg");
        const char* mesa_env = std::getenv("MESA_SHADER_CACHE_DIR");
        const char* xdg_env = std::getenv("XDG_CACHE_HOME");
        CliRun run;
        run.command =
            "cd " + test::shell_quote(dir_.string()) +
            " && ACETATE_VALIDATION=1 MESA_SHADER_CACHE_DIR=" +
            test::shell_quote(mesa_env && *mesa_env ? mesa_env : (cache / "mesa").string()) +
            " XDG_CACHE_HOME=" +
            test::shell_quote(xdg_env && *xdg_env ? xdg_env : (cache / "xdg").string()) +
            " LD_DEBUG=files LD_DEBUG_OUTPUT=" + test::shell_quote((ld_dir / "ld").string()) + " " +
            test::signer_environment() + " " + env + " " + test::shell_quote(ACETATE_CLI_PATH) +
            " render " + args + " --plugin-path " + test::shell_quote(plugins_.string());
        const int raw = std::system((run.command + " >" + test::shell_quote(out_file.string()) +
                                     " 2>" + test::shell_quote(err_file.string()) + " </dev/null")
                                        .c_str());
        run.code = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
        run.out = test::read_file(out_file);
        run.err = test::read_file(err_file);
        for (const auto& item : fs::directory_iterator(ld_dir))
            run.ld_log += test::read_file(item.path());
        return run;
    }

    // Whether the process dlopen'ed the private copy of the plugin (the linker logs
    // "file=<path>"). Under a policy the loader maps the file it checked through the
    // descriptor it holds open, so the copy appears as /proc/self/fd/N (no other library of
    // this process is opened that way).
    static bool opened_the_copy(const CliRun& run, const fs::path& file) {
        return contains(run.ld_log, "file=" + file.string()) ||
               contains(run.ld_log, "file=/proc/self/fd/");
    }

    // A registry at `file` where the probe copy (byte-identical to the plugin copy) is
    // VALIDATED, recorded through the registry API as the harness would.
    void write_validated_registry(const fs::path& file) {
        const fs::path probe = dir_ / "probe" / "lighting.so";
        EffectDescriptor d;
        {
            PluginLoader loader({});
            auto plugin = loader.load_file(probe);
            ASSERT_TRUE(plugin) << plugin.error().message;
            d = plugin.value()->descriptor;
        }
        ASSERT_EQ(d.id, "acetate.lighting");
        ASSERT_FALSE(d.source_digest.empty()) << "lighting.so was built without a source digest";
        auto sha = file_sha256(probe);
        ASSERT_TRUE(sha) << sha.error().message;
        ASSERT_EQ(sha.value(), file_sha256(plugin_file()).value());
        StageEvidence run;
        run.harness_version = "policy-test";
        run.summary = "recorded by cli_policy_test";
        run.counts = {{"PASS", 1}};
        Registry r;
        const std::string version = d.version_string();
        SignOff review{"policy-test@example.org", utc_now_iso8601(), "", d.source_digest, ""};
        test::sign(review, d.id, version, ValidationStage::Reviewed);
        ASSERT_TRUE(r.record_review(d.id, version, *sha, d.source_digest, review));
        ASSERT_TRUE(r.record_evidence(d.id, version, *sha, d.source_digest,
                                      ValidationStage::AlphaTested, run));
        ASSERT_TRUE(r.record_evidence(d.id, version, *sha, d.source_digest,
                                      ValidationStage::Integrated, run));
        SignOff promotion{"policy-test@example.org", utc_now_iso8601(), "", d.source_digest, ""};
        test::sign(promotion, d.id, version, ValidationStage::Validated);
        ASSERT_TRUE(r.promote(d.id, version, promotion));
        ASSERT_TRUE(r.is_validated(d.id, *sha));
        ASSERT_TRUE(r.save(file));
        validated_sha_ = *sha;
    }

    fs::path dir_, plugins_;
    std::string validated_sha_;
};

// (a) Nothing validated: refused in one line, the library never opened, nothing written.
TEST_F(HostPolicy, AnEmptyRegistryRefusesThePluginInOneLine) {
    const fs::path registry = dir_ / "no-such-registry.json";
    const CliRun run =
        render("scene.json -o out.png --registry " + test::shell_quote(registry.string()));
    EXPECT_EQ(run.code, 1) << run.describe();
    const auto lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    for (const std::string& part :
         {std::string("acetate: scene.json: floors[0].effects[0]"), std::string("acetate.lighting"),
          std::string("UNVALIDATED"), plugin_file().string(),
          "registry " + registry.string() + " (no such file)",
          std::string("not VALIDATED for this binary"), std::string("--allow-unvalidated")})
        EXPECT_TRUE(contains(lines[0], part)) << "missing \"" << part << "\": " << lines[0];
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    EXPECT_FALSE(opened_the_copy(run, plugin_file())) << run.ld_log;
    EXPECT_FALSE(fs::exists(registry)) << "the reader must not create the registry";
}

// (b) VALIDATED for this exact binary: loads and renders, with --registry or ACETATE_REGISTRY.
TEST_F(HostPolicy, AValidatedBinaryRenders) {
    const fs::path registry = dir_ / "registry.json";
    write_validated_registry(registry);
    if (HasFatalFailure()) return;

    CliRun run = render("scene.json -o out.png --registry " + test::shell_quote(registry.string()));
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(run.err.empty()) << run.describe();
    EXPECT_TRUE(fs::exists(dir_ / "out.png")) << run.describe();
    EXPECT_TRUE(opened_the_copy(run, plugin_file())) << run.describe();

    run =
        render("scene.json -o env.png", "ACETATE_REGISTRY=" + test::shell_quote(registry.string()));
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(run.err.empty()) << run.describe();
    EXPECT_TRUE(fs::exists(dir_ / "env.png")) << run.describe();

    // --registry wins over ACETATE_REGISTRY.
    test::write_text(dir_ / "broken.json", "{ not a registry");
    run = render("scene.json -o flag.png --registry " + test::shell_quote(registry.string()),
                 "ACETATE_REGISTRY=" + test::shell_quote((dir_ / "broken.json").string()));
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(fs::exists(dir_ / "flag.png")) << run.describe();
}

// Revocations that cannot be read refuse every sign-off, through the program as users run it:
// a FIFO in revoked_keys' place neither hangs the render nor is ignored (which would switch
// revocation off); the plugin is refused in one line and never opened.
TEST_F(HostPolicy, RevocationsThatCannotBeReadRefuseAValidatedBinary) {
    const fs::path registry = dir_ / "registry.json";
    write_validated_registry(registry);
    if (HasFatalFailure()) return;
    const fs::path keys = dir_ / "keys";
    fs::create_directories(keys);
    fs::copy_file(test::test_signer().allowed_signers, keys / "allowed_signers");
    ASSERT_EQ(::mkfifo((keys / "revoked_keys").c_str(), 0600), 0);
    const CliRun run =
        render("scene.json -o out.png --registry " + test::shell_quote(registry.string()) +
               " --allowed-signers " + test::shell_quote((keys / "allowed_signers").string()));
    EXPECT_EQ(run.code, 1) << run.describe();
    const auto lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    EXPECT_TRUE(
        contains(lines[0], "its signature cannot be checked: " + (keys / "revoked_keys").string() +
                               ": not a regular file (a FIFO)"))
        << lines[0];
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    EXPECT_FALSE(opened_the_copy(run, plugin_file())) << run.ld_log;
}

// Writing the registry is not enough: the same entry with its promotion's signature removed
// (a forged VALIDATED), or verified with keys that do not list the signer, is refused in one
// line naming the entry and the sign-off, the library never opened.
TEST_F(HostPolicy, AnEntryWhoseSignatureDoesNotHoldIsRefused) {
    const fs::path registry = dir_ / "registry.json";
    write_validated_registry(registry);
    if (HasFatalFailure()) return;
    std::string text = test::read_file(registry);
    const size_t promotion = text.find("\"promotion\"");
    ASSERT_NE(promotion, std::string::npos) << text;
    const size_t signature = text.find(",\n        \"signature\"", promotion);
    ASSERT_NE(signature, std::string::npos) << text;
    text.erase(signature,
               text.find('"', text.find("-----END SSH SIGNATURE-----", signature)) + 1 - signature);
    test::write_text(dir_ / "forged.json", text);

    struct Refusal {
        std::string registry_flag, expected;
    };
    const std::vector<Refusal> refusals = {
        {"--registry " + test::shell_quote((dir_ / "forged.json").string()),
         "acetate.lighting 1.0.0 is INTEGRATED for this binary: the promotion by "
         "policy-test@example.org is not trusted: its signature is missing"},
        {"--registry " + test::shell_quote(registry.string()) + " --allowed-signers " +
             test::shell_quote(
                 (fs::path(ACETATE_SOURCE_VALIDATION_DIR) / "allowed_signers").string()),
         "acetate.lighting 1.0.0 is UNVALIDATED for this binary: the review by "
         "policy-test@example.org is not trusted: its signature was made by a key that "
         "allowed_signers does not list"}};
    for (const Refusal& r : refusals) {
        const CliRun run = render("scene.json -o out.png " + r.registry_flag);
        EXPECT_EQ(run.code, 1) << run.describe();
        const auto lines = test::nonempty_lines(run.err);
        ASSERT_EQ(lines.size(), 1u) << run.describe();
        EXPECT_TRUE(contains(lines[0], r.expected)) << lines[0];
        EXPECT_FALSE(opened_the_copy(run, plugin_file())) << run.describe();
        EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    }
}

// (c) One byte changed after validation: another binary, refused before it is opened.
TEST_F(HostPolicy, AChangedBinaryIsRefused) {
    const fs::path registry = dir_ / "registry.json";
    write_validated_registry(registry);
    if (HasFatalFailure()) return;
    std::string bytes = test::read_file(plugin_file());
    ASSERT_FALSE(bytes.empty());
    bytes.back() = char(bytes.back() ^ 0xff);
    test::write_text(plugin_file(), bytes);
    auto changed_sha = file_sha256(plugin_file());
    ASSERT_TRUE(changed_sha);
    ASSERT_NE(changed_sha.value(), validated_sha_);

    const CliRun run =
        render("scene.json -o out.png --registry " + test::shell_quote(registry.string()));
    EXPECT_EQ(run.code, 1) << run.describe();
    const auto lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    for (const std::string& part :
         {std::string("acetate.lighting"), plugin_file().string(),
          std::string("not VALIDATED for this binary"),
          "SHA-256 " + changed_sha->substr(0, 12),  // the binary it has
          std::string("UNVALIDATED for this binary"),
          "VALIDATED for " + validated_sha_.substr(0, 12),  // the binary the registry has
          std::string("--allow-unvalidated")})
        EXPECT_TRUE(contains(lines[0], part)) << "missing \"" << part << "\": " << lines[0];
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    EXPECT_FALSE(opened_the_copy(run, plugin_file())) << run.ld_log;
}

// (d) --allow-unvalidated: loads it anyway, with one warning line naming it.
TEST_F(HostPolicy, AllowUnvalidatedLoadsWithAWarning) {
    const fs::path registry = dir_ / "no-such-registry.json";
    const CliRun run = render("scene.json -o out.png --allow-unvalidated --registry " +
                              test::shell_quote(registry.string()));
    EXPECT_EQ(run.code, 0) << run.describe();
    const auto lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    EXPECT_EQ(lines[0].rfind("acetate: warning: loading unvalidated plugin acetate.lighting (" +
                                 plugin_file().string() + "): ",
                             0),
              0u)
        << lines[0];
    EXPECT_TRUE(contains(lines[0], "UNVALIDATED")) << lines[0];
    EXPECT_TRUE(fs::exists(dir_ / "out.png")) << run.describe();
    EXPECT_TRUE(opened_the_copy(run, plugin_file())) << run.describe();
}

// A validated plugin needs no flag: --allow-unvalidated then adds no warning.
TEST_F(HostPolicy, AllowUnvalidatedIsSilentForAValidatedBinary) {
    const fs::path registry = dir_ / "registry.json";
    write_validated_registry(registry);
    if (HasFatalFailure()) return;
    const CliRun run = render("scene.json -o out.png --allow-unvalidated --registry " +
                              test::shell_quote(registry.string()));
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(run.err.empty()) << run.describe();
}

// (e) A malformed registry is bad input: one line naming the file, before anything renders.
TEST_F(HostPolicy, AMalformedRegistryIsOneLineNamingTheFile) {
    const fs::path registry = dir_ / "registry.json";
    test::write_text(registry, "{ \"format\": \"acetate-registry/1\", \"plugins\": [ \n");
    CliRun run = render("scene.json -o out.png --registry " + test::shell_quote(registry.string()));
    EXPECT_EQ(run.code, 1) << run.describe();
    auto lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    EXPECT_TRUE(contains(lines[0], registry.string())) << lines[0];
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    EXPECT_FALSE(opened_the_copy(run, plugin_file())) << run.ld_log;

    // A hand edit that claims VALIDATED without the records is malformed too, even with
    // --allow-unvalidated.
    const std::string sha = file_sha256(plugin_file()).value();
    test::write_text(registry, R"({"format": "acetate-registry/1", "plugins": [
  {"id": "acetate.lighting", "version": "1.0.0", "stage": "VALIDATED",
   "binary_sha256": ")" + sha + R"(", "source_digest": ")" +
                                   sha + R"("}]})");
    run = render("scene.json -o out.png --allow-unvalidated --registry " +
                 test::shell_quote(registry.string()));
    EXPECT_EQ(run.code, 1) << run.describe();
    lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    EXPECT_TRUE(contains(lines[0], registry.string() + ": plugins[0]")) << lines[0];
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

// (f) A scene without plugins involves no policy: the registry is not even read.
TEST_F(HostPolicy, ASceneWithoutPluginsNeedsNoRegistry) {
    CliRun run = render("plain.json -o empty.png --registry " +
                        test::shell_quote((dir_ / "no-such-registry.json").string()));
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(run.err.empty()) << run.describe();
    EXPECT_TRUE(fs::exists(dir_ / "empty.png"));

    test::write_text(dir_ / "broken.json", "{ not a registry");
    run = render("plain.json -o broken.png --registry " +
                 test::shell_quote((dir_ / "broken.json").string()));
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(fs::exists(dir_ / "broken.png"));
}

// Neither --registry nor ACETATE_REGISTRY: the build tree's registry decides. Whatever it
// holds (a harness run may have validated the build's lighting.so, whose bytes the copy has),
// the outcome is the one it implies, and a refusal names that file.
TEST_F(HostPolicy, WithoutFlagOrEnvironmentTheBuildTreeRegistryDecides) {
    ::unsetenv("ACETATE_REGISTRY");
    const fs::path default_file = registry_path(std::nullopt);
    const CliRun run = render("scene.json -o out.png", "env -u ACETATE_REGISTRY");
    const auto lines = test::nonempty_lines(run.err);
    auto registry = Registry::load(default_file);
    const std::string sha = file_sha256(plugin_file()).value();
    if (registry && registry->is_validated("acetate.lighting", sha)) {
        EXPECT_EQ(run.code, 0) << run.describe();
        EXPECT_TRUE(run.err.empty()) << run.describe();
        EXPECT_TRUE(fs::exists(dir_ / "out.png")) << run.describe();
    } else {
        EXPECT_EQ(run.code, 1) << run.describe();
        ASSERT_EQ(lines.size(), 1u) << run.describe();
        EXPECT_TRUE(contains(lines[0], default_file.string())) << lines[0];
        EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    }
}

// A refused plugin fails its scene only: the other scenes render, the exit status is 1.
TEST_F(HostPolicy, ARefusedSceneLetsTheOthersRender) {
    const CliRun run = render("plain.json scene.json plain.json -o out.png --registry " +
                              test::shell_quote((dir_ / "no-such-registry.json").string()));
    EXPECT_EQ(run.code, 1) << run.describe();
    const auto lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u) << run.describe();
    EXPECT_TRUE(contains(lines[0], "scene.json: floors[0].effects[0]")) << lines[0];
    EXPECT_TRUE(fs::exists(dir_ / "out.scene0.png")) << run.describe();
    EXPECT_FALSE(fs::exists(dir_ / "out.scene1.png"));
    EXPECT_TRUE(fs::exists(dir_ / "out.scene2.png")) << run.describe();
}

// The loader itself: the hook runs before the file is opened, for load() and load_file().
TEST_F(HostPolicy, TheLoaderAsksBeforeOpening) {
    std::vector<std::pair<std::string, fs::path>> asked;
    PluginLoader loader({plugins_});
    loader.set_admission(
        [&](const std::string& id, const fs::path& file, const fs::path&) -> Result<void> {
            asked.emplace_back(id, file);
            return make_error(ErrorCode::InvalidInput, "refused by the test");
        });
    // A library under another name: refused, it is never opened (dlopen'ed). (A file that is
    // not a library at all is refused before the hook, as the loader's own checks find it.)
    const fs::path junk = dir_ / "junk.so";
    fs::copy_file(fs::path(ACETATE_PLUGIN_DIR) / "bloom.so", junk);
    auto by_file = loader.load_file(junk);
    ASSERT_FALSE(by_file);
    EXPECT_EQ(by_file.error().message, "refused by the test");
    auto by_id = loader.load("acetate.lighting");
    ASSERT_FALSE(by_id);
    EXPECT_EQ(by_id.error().message, "refused by the test");
    ASSERT_EQ(asked.size(), 2u);
    EXPECT_EQ(asked[0], std::make_pair(std::string(), junk));
    EXPECT_EQ(asked[1], std::make_pair(std::string("acetate.lighting"), plugin_file()));
    EXPECT_EQ(loader.loaded_count(), 0u);

    // Admitted: loaded, and asked once per id.
    asked.clear();
    loader.set_admission(
        [&](const std::string& id, const fs::path& file, const fs::path&) -> Result<void> {
            asked.emplace_back(id, file);
            return {};
        });
    ASSERT_TRUE(loader.load("acetate.lighting"));
    ASSERT_TRUE(loader.load("acetate.lighting"));
    EXPECT_EQ(asked.size(), 1u);
    EXPECT_EQ(loader.loaded_count(), 1u);
}

// The policy judges the bytes that get loaded: whatever `change` does to the plugin file from
// inside the hook, after the check, the checked bytes are what loads, named as the user knows
// the file, with the digest the policy saw. Returns the file's bytes after the change.
void expect_the_checked_bytes_load(PluginLoader& loader, const fs::path& plugin,
                                   const std::function<void(const fs::path&)>& change) {
    const auto expected = file_sha256(plugin);
    ASSERT_TRUE(expected);
    std::string checked;
    loader.set_admission(
        [&](const std::string&, const fs::path& file, const fs::path& contents) -> Result<void> {
            auto sha = file_sha256(contents);
            if (!sha) return sha.error();
            checked = sha.value();
            change(file);
            return {};
        });
    auto loaded = loader.load("acetate.lighting");
    ASSERT_TRUE(loaded) << loaded.error().message;
    EXPECT_EQ(checked, expected.value());
    EXPECT_EQ(loaded.value()->binary_sha256, expected.value());
    EXPECT_EQ(loaded.value()->file, plugin);
    EXPECT_EQ(loaded.value()->descriptor.id, "acetate.lighting");
    EXPECT_EQ(test::read_file(plugin), "not an ELF file");  // the change did happen
}

// A file replaced on disk (a new inode) after the check.
TEST_F(HostPolicy, TheFileLoadedIsTheFileChecked) {
    PluginLoader loader({plugins_});
    expect_the_checked_bytes_load(loader, plugin_file(), [&](const fs::path& file) {
        test::write_text(dir_ / "swap.tmp", "not an ELF file");
        fs::rename(dir_ / "swap.tmp", file);
    });
}

// A file rewritten in place (the same inode) after the check: held open, it would be mapped
// with the new bytes; the sealed copy the policy judged is what loads.
TEST_F(HostPolicy, AFileRewrittenInPlaceAfterTheCheckIsNotWhatLoads) {
    PluginLoader loader({plugins_});
    expect_the_checked_bytes_load(loader, plugin_file(), [](const fs::path& file) {
        std::ofstream rewrite(file, std::ios::binary | std::ios::trunc);
        rewrite << "not an ELF file";
    });
}

// Two plugins under a policy in one process: each is the library it names (the dynamic
// linker knows pinned files by their /proc/self/fd/N name, which must never be reused).
TEST_F(HostPolicy, TwoPinnedPluginsStayApart) {
    fs::copy_file(fs::path(ACETATE_PLUGIN_DIR) / "bloom.so", plugins_ / "bloom.so");
    PluginLoader loader({plugins_});
    loader.set_admission(
        [](const std::string&, const fs::path&, const fs::path&) -> Result<void> { return {}; });
    auto lighting = loader.load("acetate.lighting");
    ASSERT_TRUE(lighting) << lighting.error().message;
    auto bloom = loader.load("acetate.bloom");
    ASSERT_TRUE(bloom) << bloom.error().message;
    EXPECT_EQ(lighting.value()->descriptor.id, "acetate.lighting");
    EXPECT_EQ(bloom.value()->descriptor.id, "acetate.bloom");
    EXPECT_NE(lighting.value()->api, bloom.value()->api);
}

// The embedding API (acetate/host/host.hpp) carries the same policy as the CLI: the same
// refusal line for an unvalidated plugin (only the advice on loading anyway differs), the
// plugin loaded once VALIDATED, and the scene rendered, read back and written through it.
TEST_F(HostPolicy, TheEmbeddingApiRefusesAndLoadsAsTheCliDoes) {
    host::HostOptions options;
    options.validation = true;
    options.pipeline_cache = false;
    options.plugin_directories = {plugins_};
    options.allowed_signers = test::test_signer().allowed_signers;
    options.registry = dir_ / "no-such-registry.json";
    {
        const CliRun cli = render("scene.json -o out.png --registry " +
                                  test::shell_quote(options.registry->string()));
        ASSERT_EQ(cli.code, 1) << cli.describe();
        const std::string cli_line = test::nonempty_lines(cli.err).at(0);
        const std::string advice = "; run acetate-harness validate";
        ASSERT_NE(cli_line.find(advice), std::string::npos) << cli_line;

        auto host = host::Host::create(options);
        ASSERT_TRUE(host) << host.error().message;
        auto scene = (*host)->load_scene_file(dir_ / "scene.json");
        ASSERT_FALSE(scene);
        const std::string& line = scene.error().message;
        // The CLI's line is "acetate: " and the scene's path as given on its command line.
        const std::string refusal = cli_line.substr(0, cli_line.find(advice))
                                        .substr(std::string("acetate: scene.json").size());
        EXPECT_EQ(line.substr(0, line.find(advice)), (dir_ / "scene.json").string() + refusal)
            << line << "\n"
            << cli_line;
        EXPECT_TRUE(contains(line, "or set HostOptions::allow_unvalidated")) << line;
        EXPECT_EQ(line.find('\n'), std::string::npos) << line;
        EXPECT_EQ(scene.error().code, host::ErrorCode::PluginRefused);
        // The same, as values a program can act on.
        EXPECT_EQ(scene.error().file, (dir_ / "scene.json").string());
        EXPECT_EQ(scene.error().field, "floors[0].effects[0]");
        EXPECT_EQ(scene.error().plugin, "acetate.lighting");
        EXPECT_EQ(scene.error().floor, std::optional<uint32_t>(0u));
        // Asked for, the scene loads without the refused effect (as if not listed) and says so.
        host::SceneOptions leave_out;
        leave_out.leave_out_refused_effects = true;
        auto without = (*host)->load_scene_file(dir_ / "scene.json", leave_out);
        auto plain = (*host)->load_scene_text(scene_text(false), dir_, "plain.json");
        ASSERT_TRUE(without && plain) << (without ? plain.error() : without.error()).message;
        ASSERT_EQ((*without)->left_out_effects().size(), 1u);
        EXPECT_EQ((*without)->left_out_effects()[0].message, line);
        ASSERT_TRUE((*without)->render() && (*plain)->render());
        EXPECT_EQ((*without)->read_frame()->rgba, (*plain)->read_frame()->rgba);
    }

    options.registry = dir_ / "registry.json";
    write_validated_registry(*options.registry);
    if (HasFatalFailure()) return;
    auto host = host::Host::create(options);
    ASSERT_TRUE(host) << host.error().message;
    auto scene = (*host)->load_scene_file(dir_ / "scene.json");
    ASSERT_TRUE(scene) << scene.error().message;
    EXPECT_EQ((*scene)->floor_count(), 1u);
    EXPECT_EQ((*scene)->floor_name(0), "ground");
    EXPECT_FALSE((*scene)->read_frame()) << "nothing rendered yet";
    EXPECT_FALSE((*scene)->set_active_floor(1));
    EXPECT_FALSE((*scene)->set_time(std::numeric_limits<double>::infinity()));
    ASSERT_TRUE((*scene)->set_time(2.5));
    auto stats = (*scene)->render();
    ASSERT_TRUE(stats) << stats.error().message;
    EXPECT_EQ(stats->time, 2.5);
    EXPECT_EQ(stats->targets_allocated + stats->shaders_compiled + stats->pipelines_created, 0u);
    auto frame = (*scene)->read_frame();
    ASSERT_TRUE(frame) << frame.error().message;
    ASSERT_EQ(frame->width, 16u);
    ASSERT_EQ(frame->rgba.size(), size_t(16) * 16 * 4);
    // Lit by the plugin: the tile's 0.4 grey is changed where the light falls.
    EXPECT_NE(frame->rgba[(8 * 16 + 8) * 4], 0.4f);
    ASSERT_TRUE((*scene)->write_frame(dir_ / "api.png"));
    EXPECT_TRUE(fs::exists(dir_ / "api.png"));
    EXPECT_FALSE((*scene)->write_frame(dir_ / "api.tiff"));

    // A description in memory, its images found from the folder given.
    auto from_text = (*host)->load_scene_text(scene_text(true), dir_, "inline.json");
    ASSERT_TRUE(from_text) << from_text.error().message;
    auto bad = (*host)->load_scene_text("{\"format\": \"acetate-scene/1\"}", dir_, "inline.json");
    ASSERT_FALSE(bad);
    EXPECT_TRUE(contains(bad.error().message, (dir_ / "inline.json").string()))
        << bad.error().message;
}

}  // namespace
}  // namespace acetate
