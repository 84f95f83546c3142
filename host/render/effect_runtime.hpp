#pragma once
// Effect instances at run time: what build() declared, compiled into pipelines, with their
// targets, uniforms and floor data on the GPU. Made at load (effects_at_load); recorded per
// frame with no allocation, loading or compiling.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/pixel_rect.hpp"
#include "core/view_transform.hpp"
#include "plugins/effect_graph.hpp"
#include "plugins/plugin_loader.hpp"
#include "plugins/resolve_params.hpp"
#include "render/effect_frame_layout.hpp"
#include "render/frame_stats.hpp"
#include "scene/scene.hpp"
#include "vulkan/gpu_image.hpp"
#include "vulkan/gpu_timer.hpp"

namespace acetate {

class VulkanContext;
class Renderer;

// One input of a pass, resolved at load, so a frame binds it without looking up a name: the
// image itself (a target or texture of the instance; a mask of its floor, or a transparent
// texture where the floor has none, set by bind_pass_masks once the masks are on the GPU), or
// "previous", which changes with the frame's ping-pong.
struct PassInput {
    const GpuImage* image = nullptr;  // null: "previous"
    std::string mask_kind;            // a mask input: its kind, until bind_pass_masks
};

struct EffectPassRuntime {
    std::string label;  // "floor2.acetate.bloom.down3"
    VkPipeline pipeline = VK_NULL_HANDLE;
    std::vector<PassInput> inputs;  // in binding order
    GpuImage* target = nullptr;     // what it writes: a target of the instance; null: "result"
    uint32_t blend = 0;
    uint32_t instance_count = 0;  // instanced quads; 0 for a fullscreen pass
    uint32_t instance_data_offset = 0;
    uint64_t instanced_pixels =
        0;                   // sum of the quads' areas on the output (count_instanced_pixels)
    bool from_glsl = false;  // compiled from GLSL; false: given as SPIR-V (not checkable)
    GpuBuffer uniforms;      // the frame block, laid out as the instance's frame_layout says
};

struct EffectInstance {
    std::shared_ptr<LoadedPlugin> plugin;
    size_t scene_index = 0;    // its place in the scene's list (floor's effects, or global)
    std::string graph_digest;  // effect_graph_digest of what build() declared
    std::string label;         // "floor2.acetate.lighting" / "global.acetate.bloom"
    int64_t floor = -1;        // -1: global
    bool expanding = false;
    ParamVectors params;                // resolved, clamped; 4 floats per parameter
    std::vector<double> phase_periods;  // declared phases (seconds), in declaration order
    EffectFrameLayout frame_layout;     // its passes' frame block, for these counts
    std::optional<uint32_t> reach;      // declared reach of an expanding effect (pixels)
    std::vector<EffectPassRuntime> passes;
    std::map<std::string, GpuImage*> targets;  // by declared name; owned by EffectTargets
    std::map<std::string, GpuImage> textures;  // add_texture(), this instance's own
    GpuBuffer floor_data;                      // empty buffer if the plugin set none
    bool has_floor_data = false;
    GpuBuffer lights;  // EffectLightGpu per light of the floor; empty buffer if none
    bool has_lights = false;
};

// Intermediate targets shared by instances of one plugin on different floors (floors run one
// after the other, so one set serves them all): keyed by plugin id, name and divisor.
class EffectTargets {
  public:
    Result<GpuImage*> get(VulkanContext& context, const std::string& plugin_id,
                          const GraphTarget& target, uint32_t canvas_width, uint32_t canvas_height,
                          VkFormat format);
    std::vector<const GpuImage*> images() const;
    std::vector<GpuImage*> images();

  private:
    std::map<std::string, std::unique_ptr<GpuImage>> images_;
};

// The Vulkan format of an ACETATE_FORMAT_* target; ACETATE_FORMAT_FLOOR is `floor_format`.
VkFormat target_vk_format(uint32_t format, VkFormat floor_format);

// What create_effect_instance needs besides the scene and the effect.
struct InstanceSetup {
    VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT;  // the floor's images
    EffectTargets* targets = nullptr;
    bool checked_builtins = false;      // compile GLSL with checked_builtins_glsl()
    const FloorMasks* masks = nullptr;  // the floor's mask composites, for read_mask
    // The camera build() is told of (its scale and output size) and whose output size targets
    // are made at; width 0: the whole canvas at scale 1.
    ViewTransform view;
};

// An instance after its plugin's build() and before anything of it is on the GPU: what a live
// parameter change compares (by graph_digest) with the running instance.
struct PreparedInstance {
    std::unique_ptr<EffectInstance> instance;  // plugin, params, label, reach, phases, digest
    EffectGraph graph;
    std::vector<AcetateLightInfo> lights;  // the floor's, as build() was told them
};

// Loads the plugin an EffectRef names and runs its build() for `floor` (-1: global): the
// parameters resolved and checked, the graph checked. Allocates nothing on the device.
Result<PreparedInstance> prepare_effect_instance(Renderer& renderer, const SceneDesc& scene,
                                                 const EffectRef& ref, int64_t floor,
                                                 const InstanceSetup& setup);

// Loads the plugin an EffectRef names, builds its instance for `floor` (-1: global), compiles
// its passes and allocates what they write.
Result<std::unique_ptr<EffectInstance>> create_effect_instance(Renderer& renderer,
                                                               const SceneDesc& scene,
                                                               const EffectRef& ref, int64_t floor,
                                                               const InstanceSetup& setup);
// The same from an instance prepare_effect_instance made (its build() already run).
Result<std::unique_ptr<EffectInstance>> create_effect_instance(Renderer& renderer,
                                                               const SceneDesc& scene,
                                                               const EffectRef& ref, int64_t floor,
                                                               const InstanceSetup& setup,
                                                               PreparedInstance prepared);

// The pixels a floor's tiles cover (the union of their rects, clipped to the canvas).
PixelRect floor_coverage_bounds(const SceneDesc& scene, size_t floor);

// What an instance reads and writes in one frame.
struct EffectIo {
    GpuImage* previous = nullptr;  // the floor (or accumulation) so far
    GpuImage* result = nullptr;    // where "result" goes (the other ping-pong image)
    PixelRect result_scissor;      // the area "result" passes shade
    // When set: "result" passes draw once per rect instead (disjoint, inside result_scissor).
    const std::vector<PixelRect>* result_rects = nullptr;
    double time = 0;  // seconds; phases and the clock are reduced from it in double
    uint32_t canvas_width = 0, canvas_height = 0;  // of "previous" and "result": the output
    // The camera (the block AcetateView) and the scene's canvas size.
    ViewTransform view;
    uint32_t scene_width = 0, scene_height = 0;
    bool warm_up = false;       // shade one pixel per pass (load-time pipeline warm-up)
    GpuTimer* timer = nullptr;  // marks each pass with its label when the frame is timed
};

// Counts each instanced pass's quads (their floor_data rects, scene pixels) as the output of
// `view` shows them: EffectPassRuntime::instanced_pixels. At load and whenever the camera moves.
void count_instanced_pixels(EffectInstance& instance, const ViewTransform& view);

// Resolves the instance's mask inputs to images: `masks` are its floor's (none for a global
// effect); a kind missing there reads `blank` (transparent). Called once at load.
void bind_pass_masks(EffectInstance& instance, const std::map<std::string, GpuImage>* masks,
                     const GpuImage& blank);

// What binding `binding` of a pass reads ("previous" is io.previous) and what the pass writes
// (its own target, or io.result): the uses a compiled frame declares for it.
const GpuImage* effect_pass_input(const EffectPassRuntime& pass, size_t binding,
                                  const EffectIo& io);
GpuImage* effect_pass_output(const EffectPassRuntime& pass, const EffectIo& io);

// Records pass `index` of an instance, its inputs already sampled-read and its output already
// a colour attachment (a compiled frame's planned barriers); counts the pass and the pixels it
// shades into `report`. Looks up no name and allocates nothing.
void record_effect_pass(VkCommandBuffer cmd, Renderer& renderer, EffectInstance& instance,
                        size_t index, const EffectIo& io, FloorFrameReport& report);

}  // namespace acetate
