#include "references.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "case_batch.hpp"
#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/json_fields.hpp"
#include "core/sha256.hpp"
#include "core/strict_json.hpp"
#include "registry.hpp"
#include "scene/scene.hpp"
#include "validate.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using nlohmann::ordered_json;
using namespace json_fields;

constexpr uint32_t kWidth = 128, kHeight = 80;
constexpr float kLaterTime = 2.5f;
// The reference cases' seed: fixed, so they render the same scene at any --seed.
constexpr uint64_t kReferenceSeed = 0x9e1de5;

std::string time_label(float t) {
    return t == 0.0f ? "t0" : fmt::format("t{}", t);
}

double number(const json& j, const std::string& path, std::string_view key, double low,
              double high) {
    const json& v = j.at(std::string(key));
    if (!v.is_number() || !(v.get<double>() >= low && v.get<double>() <= high))
        fail(field(path, key), fmt::format("must be a number from {} to {}", low, high));
    return v.get<double>();
}

std::string filled_text(const json& j, const std::string& path, std::string_view key) {
    return non_empty_text(required(j, path, key), field(path, key));
}

ReferenceSet read_manifest(const json& j, const fs::path& directory) {
    expect_object(
        j, "",
        {"format", "plugin", "version", "source_digest", "blessed_by", "at", "gates", "images"},
        {"scenes"});
    if (filled_text(j, "", "format") != kReferencesFormat)
        fail("format", fmt::format("is not \"{}\"", kReferencesFormat));
    ReferenceSet set;
    set.directory = directory;
    set.plugin = filled_text(j, "", "plugin");
    set.version = filled_text(j, "", "version");
    set.source_digest = filled_text(j, "", "source_digest");
    set.blessed_by = filled_text(j, "", "blessed_by");
    set.at = filled_text(j, "", "at");
    const json& g = j.at("gates");
    expect_object(g, "gates", {"warn", "fail", "fail_percent", "hard_fail"});
    set.gates.warn = number(g, "gates", "warn", 0, 1e9);
    set.gates.fail = number(g, "gates", "fail", 0, 1e9);
    set.gates.fail_percent = number(g, "gates", "fail_percent", 0, 100);
    set.gates.hard_fail = number(g, "gates", "hard_fail", 0, 1e9);
    const json& images = j.at("images");
    if (!images.is_object()) fail("images", "must be an object of case id: file name");
    for (const auto& [id, file] : images.items()) {
        const std::string path = field("images", id);
        if (!file.is_string()) fail(path, "must be a file name");
        const std::string name = file.get<std::string>();
        // A plain name in the plugin's folder: a manifest must not point anywhere else.
        if (name.empty() || name.find('/') != std::string::npos || name[0] == '.')
            fail(path, fmt::format("\"{}\" is not a file name in {}", name, directory.string()));
        set.images[id] = name;
    }
    const json scenes = j.value("scenes", json::object());
    if (!scenes.is_object()) fail("scenes", "must be an object of scene name: digest");
    for (const auto& [name, digest] : scenes.items()) {
        if (!digest.is_string()) fail(field("scenes", name), "must be a SHA-256 digest");
        set.scenes[name] = digest.get<std::string>();
    }
    return set;
}

ordered_json write_manifest(const ReferenceSet& set) {
    ordered_json images = ordered_json::object();
    for (const auto& [id, name] : set.images) images[id] = name;
    return ordered_json{{"format", kReferencesFormat},
                        {"plugin", set.plugin},
                        {"version", set.version},
                        {"source_digest", set.source_digest},
                        {"blessed_by", set.blessed_by},
                        {"at", set.at},
                        {"gates",
                         {{"warn", set.gates.warn},
                          {"fail", set.gates.fail},
                          {"fail_percent", set.gates.fail_percent},
                          {"hard_fail", set.gates.hard_fail}}},
                        {"images", images},
                        {"scenes", set.scenes}};
}

CaseResult failing_case(const std::string& id, const std::string& description,
                        const std::string& message) {
    CaseResult c;
    c.id = id;
    c.description = description;
    c.verdict = Verdict::Fail;
    c.message = message;
    CheckResult check;
    check.check = "golden";
    check.verdict = Verdict::Fail;
    check.message = message;
    c.checks.push_back(std::move(check));
    return c;
}

}  // namespace

json to_json(const ReferenceGates& g) {
    return {{"warn", g.warn},
            {"fail", g.fail},
            {"fail_percent", g.fail_percent},
            {"hard_fail", g.hard_fail}};
}

ImageRGBA contact_sheet(const std::vector<ImageRGBA>& images) {
    constexpr uint32_t kGap = 4;
    uint32_t width = 0, height = 0;
    for (const ImageRGBA& image : images) {
        width += image.width + (width ? kGap : 0);
        height = std::max(height, image.height);
    }
    ImageRGBA sheet(width, height);
    uint32_t left = 0;
    for (const ImageRGBA& image : images) {
        for (uint32_t y = 0; y < image.height; ++y)
            std::copy_n(image.pixels.begin() + size_t(y) * image.width * 4, image.width * 4,
                        sheet.pixels.begin() + (size_t(y) * width + left) * 4);
        left += image.width + kGap;
    }
    return sheet;
}

fs::path golden_output_file(const fs::path& case_directory) {
    return case_directory / "golden.exr";
}

std::vector<CaseSpec> golden_cases(const PluginInfo& plugin) {
    std::vector<std::pair<std::string, float>> runs = {{"", 0.0f}, {"", kLaterTime}};
    for (const std::string& preset : plugin.presets) runs.push_back({preset, kLaterTime});
    std::vector<CaseSpec> cases;
    for (const auto& [preset, time] : runs) {
        CaseSpec s;
        s.kind = CaseKind::Golden;
        s.id =
            fmt::format("reference/{}/{}", preset.empty() ? "defaults" : preset, time_label(time));
        s.description =
            fmt::format("the fixed reference scene at {}, t = {} s, against the blessed image",
                        preset.empty() ? "the defaults" : "preset " + preset, time);
        s.seed = case_seed(kReferenceSeed, "reference");  // one scene for every preset and time
        s.width = kWidth;
        s.height = kHeight;
        s.preset = preset;
        s.time = time;
        s.poison = Poison::None;  // a correct plugin never reads it; keep the scene fixed
        s.inputs = {{"reference", preset.empty() ? "defaults" : preset},
                    {"time", fmt::format("{}", time)}};
        cases.push_back(std::move(s));
    }
    for (const ReferenceScene& scene : plugin.reference_scenes)
        for (const float time : {0.0f, kLaterTime}) {
            CaseSpec s;
            s.kind = CaseKind::Golden;
            s.id = fmt::format("reference/scene-{}/{}", scene.name, time_label(time));
            s.description = fmt::format(
                "the plugin's own reference scene {} as written, t = {} s, against "
                "the blessed image",
                fs::path(scene.file).filename().string(), time);
            s.seed = case_seed(kReferenceSeed, s.id);  // unused: the scene is fixed
            s.width = scene.width;
            s.height = scene.height;
            s.time = time;
            s.poison = Poison::None;
            s.scene_file = scene.file;
            s.inputs = {{"reference", "scene " + scene.name}, {"time", fmt::format("{}", time)}};
            cases.push_back(std::move(s));
        }
    return cases;
}

namespace {

// One digest for a scene as it renders: its file and each image it names, in the scene's order.
Result<std::string> scene_digest(const SceneDesc& scene) {
    std::vector<fs::path> files = {scene.file};
    for (const FloorDesc& floor : scene.floors)
        for (const TileDesc& tile : floor.tiles) {
            files.push_back(tile.image);
            for (const auto& [kind, mask] : tile.masks) files.push_back(mask);
        }
    std::string digests;
    for (const fs::path& file : files) {
        auto sha = file_sha256(file);
        if (!sha) return sha.error();
        digests += sha.value() + "\n";
    }
    return sha256_hex(digests);
}

bool is_scene_name(const std::string& name) {
    return !name.empty() && std::isalnum(static_cast<unsigned char>(name[0])) &&
           std::all_of(name.begin(), name.end(), [](unsigned char c) {
               return std::islower(c) || std::isdigit(c) || c == '-' || c == '_';
           });
}

}  // namespace

Result<std::vector<ReferenceScene>> find_reference_scenes(const fs::path& root,
                                                          const std::string& plugin_id) {
    const fs::path folder = root / plugin_id / "scenes";
    std::vector<ReferenceScene> scenes;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) return scenes;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder, ec))
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    if (ec)
        return make_error(ErrorCode::Io,
                          fmt::format("{}: cannot list: {}", folder.string(), ec.message()));
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
        const std::string name = file.stem().string();
        if (!is_scene_name(name))
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: a reference scene's name is lower-case letters, "
                                          "digits, '-' and '_' (it names its cases)",
                                          file.string()));
        auto scene = parse_scene_file(fs::absolute(file));
        if (!scene) return scene.error();
        std::vector<const EffectRef*> effects;
        for (const FloorDesc& floor : scene->floors)
            for (const EffectRef& e : floor.effects) effects.push_back(&e);
        for (const EffectRef& e : scene->global_effects) effects.push_back(&e);
        if (effects.empty())
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: the scene uses no effect; a reference scene of {} "
                                          "uses it",
                                          file.string(), plugin_id));
        for (const EffectRef* e : effects)
            if (e->plugin != plugin_id)
                return make_error(ErrorCode::InvalidInput,
                                  fmt::format("{}: {}.plugin: \"{}\" is not {}; a plugin's "
                                              "reference scene uses it alone",
                                              file.string(), e->where, e->plugin, plugin_id));
        auto digest = scene_digest(scene.value());
        if (!digest) return digest.error();
        scenes.push_back(
            {name, fs::absolute(file).string(), digest.value(), scene->width, scene->height});
    }
    return scenes;
}

Result<std::optional<ReferenceSet>> load_references(const fs::path& root,
                                                    const std::string& plugin_id) {
    const fs::path directory = root / plugin_id;
    const fs::path manifest = directory / "manifest.json";
    std::error_code ec;
    if (!fs::exists(manifest, ec)) return std::optional<ReferenceSet>();
    auto parsed = read_json_file(manifest, kMaxHarnessFileBytes, "a reference manifest");
    if (!parsed) return parsed.error();
    auto read =
        read_json(manifest.string(), [&] { return read_manifest(parsed.value(), directory); });
    if (!read) return read.error();
    ReferenceSet set = std::move(read.value());
    if (set.plugin != plugin_id)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("{}: plugin: \"{}\" is not the folder's plugin \"{}\"",
                                      manifest.string(), set.plugin, plugin_id));
    for (const auto& [id, name] : set.images)
        if (!fs::is_regular_file(directory / name, ec))
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: images.{}: {} is missing", manifest.string(), id,
                                          (directory / name).string()));
    return std::optional<ReferenceSet>(std::move(set));
}

std::optional<CaseResult> attach_references(std::vector<CaseSpec>& cases,
                                            const std::optional<ReferenceSet>& set,
                                            const PluginInfo& plugin) {
    if (!set) return std::nullopt;
    const std::string bless = fmt::format(
        "review the new images (this report's reference cases show them), then bless them: "
        "acetate-harness bless {} --by NAME",
        plugin.file);
    if (set->source_digest != plugin.source_digest)
        return failing_case(
            "reference/current", "the blessed references are for this plugin's source",
            fmt::format("{}: the references in {} were blessed for source {}, the plugin's "
                        "is {}: {}",
                        plugin.id, set->directory.string(), set->source_digest.substr(0, 12),
                        plugin.source_digest.substr(0, 12), bless));
    for (const ReferenceScene& scene : plugin.reference_scenes) {
        auto blessed = set->scenes.find(scene.name);
        if (blessed == set->scenes.end() || blessed->second != scene.digest)
            return failing_case(
                "reference/current", "the blessed references are for the plugin's own scenes",
                fmt::format(
                    "{}: {} {} since the references were blessed: {}", plugin.id, scene.file,
                    blessed == set->scenes.end() ? "was added" : "or an image it names changed",
                    bless));
    }
    std::vector<std::string> missing;
    for (CaseSpec& c : cases) {
        if (c.kind != CaseKind::Golden) continue;
        auto image = set->images.find(c.id);
        if (image == set->images.end()) {
            missing.push_back(c.id);
            continue;
        }
        c.reference = {{"image", (set->directory / image->second).string()},
                       {"gates", to_json(set->gates)}};
    }
    if (missing.empty()) return std::nullopt;
    return failing_case("reference/current", "every reference case has a blessed image",
                        fmt::format("{}: {} has no image for {}: {}", plugin.id,
                                    set->directory.string(), fmt::join(missing, ", "), bless));
}

Result<ReferenceSet> bless_references(const fs::path& root, const PluginInfo& plugin,
                                      const std::vector<CaseSpec>& cases,
                                      const std::vector<CaseResult>& results,
                                      const fs::path& report_directory, const std::string& by) {
    for (const CaseResult& r : results)
        if (r.verdict != Verdict::Pass && r.verdict != Verdict::Warn && r.verdict != Verdict::Skip)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: bless refused: case {} is {}: {}; fix the plugin "
                                          "first",
                                          plugin.id, r.id, to_string(r.verdict), r.message));
    ReferenceSet set;
    set.directory = root / plugin.id;
    set.plugin = plugin.id;
    set.version = plugin.version;
    set.source_digest = plugin.source_digest;
    set.blessed_by = by;
    set.at = utc_now_iso8601();
    if (auto earlier = load_references(root, plugin.id); earlier && earlier.value())
        set.gates = earlier.value()->gates;  // a maintainer's tuned gates stay
    for (const ReferenceScene& scene : plugin.reference_scenes)
        set.scenes[scene.name] = scene.digest;
    std::error_code ec;
    fs::create_directories(set.directory, ec);
    if (ec)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot create: {}",
                                                     set.directory.string(), ec.message()));
    for (const CaseSpec& c : cases) {
        if (c.kind != CaseKind::Golden) continue;
        const fs::path rendered =
            golden_output_file(report_directory / "cases" / case_folder(c.id));
        auto bytes = read_input_file(rendered, kMaxHarnessFileBytes, "a rendered reference");
        if (!bytes) return bytes.error();
        const std::string name = case_folder(c.id) + ".exr";
        ACETATE_TRY(write_file_atomically(set.directory / name, bytes.value()));
        set.images[c.id] = name;
    }
    // Written last: a reader sees the old manifest or the new one, each naming images present.
    ACETATE_TRY(
        write_file_atomically(set.directory / "manifest.json", write_manifest(set).dump(2) + "\n"));
    return set;
}

}  // namespace acetate::harness
