#pragma once
// What every kind of case shares in its child process: the GPU session (one device, one
// renderer, the plugins under test found by id), the scenes it builds, the captures of a
// floor or of the composite before and after the effects, and the writer of the case's result
// and pictures. The kinds themselves are in case_kinds.hpp.

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
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

// A renderer whose plugin search finds exactly the files under test, on `device` (the device of
// the cases before it in this process), or on a device it opens when given none.
Result<Session> open_session(const CaseContext& c, std::unique_ptr<VulkanContext> device = nullptr);

// ---- scenes -----------------------------------------------------------------------------

// The plugin under test with the case's params and preset (or `params`, when given).
SceneEffect under_test(const CaseContext& c, nlohmann::json params = nullptr);
// The case's scene: its floors made of its inputs (pattern, lights, masks), the plugin on every
// floor or only on `plugin_floor` (a floor effect), or on the composite (a global one).
SceneLayout case_layout(const CaseContext& c, nlohmann::json params = nullptr);
// The floors that carry the plugin (none for a global effect).
std::vector<uint32_t> plugin_floors(const CaseContext& c);

// ---- captures ---------------------------------------------------------------------------

struct Capture {
    ImageRGBA input, output;
};

Result<ImageRGBA> render_floor(Compositor& comp, uint32_t floor, double time);
// What the plugin produced with floor `floor` active: that floor's target (a floor effect),
// or the composite it ran on (a global effect).
Result<ImageRGBA> plugin_output(Compositor& comp, bool global, uint32_t floor, double time);
// A floor's target before and after its effects.
Result<Capture> capture_floor(Compositor& comp, uint32_t floor, double time);
// Effect `index` alone, each judged on its own input and output: the floor's target (or the
// composite of floors 0..floor) after the effects before it, and after it too.
Result<Capture> capture_effect(Compositor& comp, bool global, uint32_t floor, double time,
                               uint32_t index);
Result<Capture> capture_global_effect(Compositor& comp, uint32_t top, double time, uint32_t index);
// The plugin under test's own input and output on `floor` (a global one: on the composite of
// floors 0..floor), between the case's neighbours.
Result<Capture> capture_plugin(Compositor& comp, const CaseContext& c, uint32_t floor);
Result<ImageRGBA> plugin_own_output(Compositor& comp, const CaseContext& c, uint32_t floor);

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
    // Adds the vulkan-validation check (SKIP when the layer was off in this process; none in a
    // case run without the layer on purpose) and sets the case's verdict. The process had
    // `messages_before` validation messages when the case began (the cases before it in the
    // same process had theirs).
    CaseResult finish(bool validation_layer_on, uint64_t messages_before);
    CaseResult result;

  private:
    const CaseContext& c_;
};

// The resident set of this process, in bytes.
uint64_t resident_bytes();

// How a scene is loaded besides the case's poison.
struct LoadOptions {
    bool checked_builtins = false;        // GLSL with checked min/max/clamp/smoothstep (Undefined)
    bool ignore_declared_reach = false;   // shade as if no reach was declared (the reach check)
    std::optional<VkFormat> format;       // instead of the case's (the format-agreement relation)
    std::optional<ViewTransform> camera;  // seen through it (the camera-region relation)
};

// Writes the layout's scene and loads it, with the case's poison. A scene the host refuses
// (the plugin's build() failed, a shader did not compile) is the case's "load" failure: it is
// recorded and the result is null, so the case stops there. Environment failures come back as
// errors.
Result<std::unique_ptr<Compositor>> load_layout(const CaseContext& c, Session& s, CaseWriter& w,
                                                const SceneLayout& layout, const std::string& name,
                                                const LoadOptions& how = {});
// The same for a scene already written.
Result<std::unique_ptr<Compositor>> load_scene(const CaseContext& c, Session& s, CaseWriter& w,
                                               const SceneDesc& scene, const LoadOptions& how = {});

// What the process does before the case's own load: `prior_loads` other scenes loaded and
// rendered (other canvases and floor counts). False when a load failed (recorded as the
// case's "load" failure).
Result<bool> render_history(const CaseContext& c, Session& s, CaseWriter& w);
// In the case's own load, before the frame that is checked: `frames - 1` frames at advancing
// times up to the case's, each floor active in turn.
Result<void> render_earlier_frames(Compositor& comp, const CaseContext& c);

}  // namespace acetate::harness
