#pragma once
// Golden references (docs/harness.md, "Golden references"): a fixed set of scenes, presets and
// times every plugin is rendered on (the `reference/...` cases), whose outputs a maintainer
// blesses after looking at them (`acetate-harness bless`). They are stored as half-float
// premultiplied EXR under <root>/<plugin id>/, with manifest.json naming the source digest they
// were blessed for and the plugin's gates. `validate` compares every later build with them:
// colour, not only alpha, is judged. A source change without new references fails the run
// with one line telling the maintainer to review and bless.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "case_spec.hpp"
#include "core/result.hpp"
#include "report.hpp"
#include "scene/image_io.hpp"

namespace acetate::harness {

// idiff-style gates on a pixel's largest channel difference |output - reference| (premultiplied
// linear RGBA, alpha too), stated per plugin in its manifest.
struct ReferenceGates {
    double warn = 1.0 / 1024.0;  // one half-float rounding at 1.0: WARN above it
    double fail = 4.0 / 255.0;   // four 8-bit steps at full scale: a pixel over it "fails"
    // FAIL when the failing pixels are more than this share of all pixels, in percent, each
    // pixel weighted by its alpha (max of the two images'): a difference where nothing is
    // covered weighs nothing.
    double fail_percent = 0.1;
    double hard_fail = 0.25;  // FAIL when any pixel differs by more
};
nlohmann::json to_json(const ReferenceGates& gates);

// manifest.json, format "acetate-references/1".
struct ReferenceSet {
    std::filesystem::path directory;  // <root>/<plugin id>
    std::string plugin, version, source_digest;
    std::string blessed_by, at;  // who blessed them, when (ISO-8601 UTC)
    ReferenceGates gates;
    std::map<std::string, std::string> images;  // case id -> file name in `directory`
    // The plugin's own scenes the images were rendered from: name -> digest (ReferenceScene);
    // a scene edited (or an image it names) since makes the references stale.
    std::map<std::string, std::string> scenes;
};

inline constexpr const char* kReferencesFormat = "acetate-references/1";

// The reference cases (kind Golden): the plugin's defaults at t = 0 and t = 2.5 s, and each
// declared preset at t = 2.5 s, all on one fixed 128x80 scene shared by every plugin; then
// each of the plugin's own scenes (plugin.reference_scenes) at t = 0 and t = 2.5 s, as
// written. Their seed does not depend on the run's, so the same cases are rendered at any
// --seed and strictness.
std::vector<CaseSpec> golden_cases(const PluginInfo& plugin);

// The plugin's own reference scenes: <root>/<plugin id>/scenes/*.json, by name. Each must be a
// valid scene that uses this plugin and no other (the harness loads only the plugin under
// test); otherwise InvalidInput naming the scene file and the field. None: an empty list.
Result<std::vector<ReferenceScene>> find_reference_scenes(const std::filesystem::path& root,
                                                          const std::string& plugin_id);

// <root>/<plugin id>/manifest.json; nullopt when that folder holds none. InvalidInput naming
// the file and the field when it is malformed; an image it names that is missing is an error
// naming the image.
Result<std::optional<ReferenceSet>> load_references(const std::filesystem::path& root,
                                                    const std::string& plugin_id);

// Gives every Golden case in `cases` its reference image and the gates, when `set` holds one
// for this source; otherwise the cases only render. Returns the failing case that stands for
// stale references (blessed for another source digest, or missing an image for a case), or
// nullopt when they are current or none were ever blessed.
std::optional<CaseResult> attach_references(std::vector<CaseSpec>& cases,
                                            const std::optional<ReferenceSet>& set,
                                            const PluginInfo& plugin);

// What `bless` writes: the rendered outputs of the Golden cases (from each case's folder under
// `report_directory`) copied to <root>/<plugin id>/ and the manifest written last, each file
// atomically; the gates of an earlier manifest are kept. Refused when a case did not pass.
Result<ReferenceSet> bless_references(const std::filesystem::path& root, const PluginInfo& plugin,
                                      const std::vector<CaseSpec>& cases,
                                      const std::vector<CaseResult>& results,
                                      const std::filesystem::path& report_directory,
                                      const std::string& by);

// The images side by side on one sheet (4 px apart, in the order given), for a person to look
// at before blessing: premultiplied linear RGBA, as save_image takes it.
ImageRGBA contact_sheet(const std::vector<ImageRGBA>& images);

// The file a Golden case's child writes its output to, in its case folder.
std::filesystem::path golden_output_file(const std::filesystem::path& case_directory);

}  // namespace acetate::harness
