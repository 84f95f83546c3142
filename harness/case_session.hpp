#pragma once
// What every kind of case shares in its child process: the GPU session (one device, one
// renderer, the plugins under test found by id), the scenes it builds, the captures of a
// floor or of the composite before and after the effects, and the writer of the case's result
// and pictures. The kinds themselves are in case_kinds.hpp.

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "case_runner.hpp"
#include "contract_checks.hpp"
#include "render/compositor.hpp"
#include "render/renderer.hpp"
#include "synthetic_inputs.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::harness {

struct Session {
    std::unique_ptr<VulkanContext> context;
    std::unique_ptr<Renderer> renderer;
};

// Opens the device and a renderer whose plugin search finds exactly the files under test.
Result<Session> open_session(const CaseContext& c);

// ---- scenes -----------------------------------------------------------------------------

// The plugin under test with the case's params and preset (or `params`, when given).
SceneEffect under_test(const CaseContext& c, nlohmann::json params = nullptr);
// Every floor carries the plugin (a floor effect) or the composite does (a global one).
SceneLayout plugin_everywhere(const CaseContext& c, nlohmann::json params = nullptr);

// ---- captures ---------------------------------------------------------------------------

struct Capture {
    ImageRGBA input, output;
};

Result<ImageRGBA> render_floor(Compositor& comp, uint32_t floor, float time);
// What the plugin produced with floor `floor` active: that floor's target (a floor effect),
// or the composite it ran on (a global effect).
Result<ImageRGBA> plugin_output(Compositor& comp, bool global, uint32_t floor, float time);
// A floor's target before and after its effects.
Result<Capture> capture_floor(Compositor& comp, uint32_t floor, float time);
// The composite of floors 0..top before and after the global effects.
Result<Capture> capture_global(Compositor& comp, uint32_t top, float time);

// ---- results ----------------------------------------------------------------------------

// The case's result: its checks and the pictures the report shows.
class CaseWriter {
  public:
    explicit CaseWriter(const CaseContext& c);

    // Saves a picture for the report (small enough to look at), returning its relative path
    // ("" when it is too large to show or could not be written).
    std::string picture(const std::string& name, const ImageRGBA& image);
    void case_picture(const std::string& role, const ImageRGBA& image);
    void add(CheckResult check, const std::map<int64_t, ImageRGBA>* heat_maps = nullptr);
    void add_all(std::vector<CheckResult> checks,
                 const std::map<std::string, std::map<int64_t, ImageRGBA>>& heat);
    // Adds the vulkan-validation check and sets the case's verdict.
    CaseResult finish();
    CaseResult result;

  private:
    const CaseContext& c_;
};

// The resident set of this process, in bytes.
uint64_t resident_bytes();

// Writes the layout's scene and loads it. A scene the host refuses (the plugin's build()
// failed, a shader did not compile) is the case's "load" failure: it is recorded and the
// result is null, so the case stops there. Environment failures come back as errors.
Result<std::unique_ptr<Compositor>> load_layout(const CaseContext& c, Session& s, CaseWriter& w,
                                                const SceneLayout& layout, const std::string& name);

}  // namespace acetate::harness
