#pragma once
// The floor compositor: per frame, for each floor up to the active one, bottom to top, draw the
// floor's tiles premultiplied (into its own target, writing stencil = 1 where they cover, or
// straight into the accumulation when it has no effects), composite with premultiplied "over"
// gated by that stencil, then write the accumulation over the canvas background to the output.
// Everything is created at load; render() allocates, loads and compiles nothing.
//
// Its files, one job each: compositor_load.cpp (load: effects, masks, targets, pipelines, the
// planner's geometry), compositor_warm_up.cpp (every pipeline drawn once at load),
// floor_recording.cpp (a frame's commands: floors, composites, global effects, the output),
// compositor.cpp (render(), read-backs and what it holds), compositor_params.cpp (live
// parameters), compositor_camera.cpp (the camera: the region and scale a frame shows). Its targets
// are a FrameTargets, its output views are in output_view.hpp, the Vulkan commands it records in
// vulkan/render_commands.hpp.

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "core/view_transform.hpp"
#include "render/compiled_frame.hpp"
#include "render/effect_runtime.hpp"
#include "render/frame_plan.hpp"
#include "render/frame_stats.hpp"
#include "render/frame_targets.hpp"
#include "render/host_pipelines.hpp"
#include "render/output_view.hpp"
#include "render/scene_resources.hpp"
#include "scene/scene.hpp"
#include "vulkan/gpu_image.hpp"
#include "vulkan/gpu_timer.hpp"

namespace acetate {

class VulkanContext;
class Renderer;

struct CompositorOptions {
    VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT;  // targets and textures; or RGBA32F
    OutputView view = OutputView::Normal;
    PlanOptions plan;                  // optimisations; all on by default
    std::set<std::string> mask_kinds;  // mask kinds some effect needs (composited at load)
    // Test hook: after a floor's tiles, paint a colour into its target, inside or outside its
    // coverage, as a contract-breaking effect would. Forces floor targets.
    struct Injection {
        std::array<float, 4> colour{0, 0, 0, 0};
        bool inside_coverage = false;
    };
    std::optional<Injection> inject;
    // A sentinel the harness fills memory with that an effect may read before writing it: every
    // intermediate target is cleared to it once at load (not between floors or frames, so what
    // one floor wrote stays for the next), and before each effect instance records, the area
    // of "result" its passes shade holds it (outside that area "result" stays 0). NaN is fine.
    // Unset: no extra clear.
    std::optional<std::array<float, 4>> poison;
    // The harness's reach check: shade expanding floors over the whole canvas, as if no effect
    // had declared a reach (set_reach), so what an effect draws past its reach shows.
    bool ignore_declared_reach = false;
    // GLSL passes are compiled with min, max, clamp and smoothstep that return NaN for a NaN
    // operand, smoothstep also for edge0 >= edge1, and texelFetch for a texel outside its
    // texture (checked_builtins_glsl()), so the
    // harness's `finite` check sees results a driver may hide. Per scene rather than in
    // RendererOptions: the pool keys shaders by their source, so checked and unchecked
    // variants live side by side in one renderer, and the harness sets both options together.
    bool checked_builtins = false;
    // Time every step of the frame on the GPU with timestamp queries (FrameStats::gpu_passes):
    // for acetate-bench. Off, a frame records no query. A device whose queue has no timestamps
    // loads anyway, untimed (gpu_timings_warning() says why).
    bool gpu_timings = false;
    // An effect whose plugin the load policy refuses is left out (recorded in left_out())
    // instead of failing the load.
    bool leave_out_refused = false;
};

// An effect entry loaded without (CompositorOptions::leave_out_refused).
struct LeftOutEntry {
    std::optional<uint32_t> floor;  // empty: a global effect
    uint32_t index = 0;             // in the scene's list
    std::string plugin, message;
};

// How the loaded scene's effect passes were given: only passes compiled from GLSL get
// checked_builtins; SPIR-V passes run as they are.
struct EffectPassCounts {
    uint32_t glsl = 0;
    uint32_t spirv = 0;
};

class Compositor {
  public:
    // Loads the plugins the scene names (only those), builds their instances, loads images,
    // composites the masks effects need, allocates targets, creates and warms every pipeline.
    // Errors name the scene file and field (e.g. a canvas over the device limit).
    static Result<std::unique_ptr<Compositor>> load(Renderer& renderer, const SceneDesc& scene,
                                                    const CompositorOptions& options);
    ~Compositor();
    Compositor(const Compositor&) = delete;
    Compositor& operator=(const Compositor&) = delete;

    // Renders floors 0..active_floor and the output. Fails with InvalidInput for a floor index
    // out of range, or when the view needs a floor target this compositor was loaded without.
    // `time` (seconds) is what effects animate with.
    Result<FrameStats> render(uint32_t active_floor, double time = 0.0);
    // Changes the view for later frames (no allocation; see render()).
    void set_view(OutputView view) { options_.view = view; }
    // Turns every effect off (or back on) for later frames: floors still go through their
    // targets, so read_active_floor() and read_accumulation() then show what the effects
    // would have been given (the validation harness's "input"). No allocation.
    void set_effects_enabled(bool enabled) { set_effects_enabled(enabled, enabled); }
    // The same, floor effects and global effects apart (the harness reads the composite the
    // floor effects made before the global effects run on it).
    void set_effects_enabled(bool floor_effects, bool global_effects) {
        effects_enabled_ = floor_effects;
        global_effects_run_ = global_effects ? UINT32_MAX : 0;
    }
    // Runs only the first `count` global effects, in the scene's order, for later frames: the
    // composite then shows what global effect `count` is given (the harness judges each global
    // effect on its own input and output). No allocation.
    void set_global_effects_run(uint32_t count) { global_effects_run_ = count; }
    // Runs only the first `count` effects of each floor, for later frames: the floor's target
    // then shows what effect `count` is given (the harness judges an effect with neighbours on
    // its floor on its own input and output). No allocation.
    void set_floor_effects_run(uint32_t count) { floor_effects_run_ = count; }
    // How many of the floor's (or, without a floor, the global) effects run before the scene's
    // effect `index`, and whether that effect runs at all: an instance that declared nothing
    // is dropped at load (water on a floor without water), so scene indices and positions in
    // the run differ. For the counts above.
    struct EffectPosition {
        uint32_t before = 0;  // instances before it that run
        bool runs = false;    // false: dropped, it changes nothing
    };
    EffectPosition effect_position(std::optional<uint32_t> floor, uint32_t index) const;

    // Float readbacks for tests and file output (premultiplied, linear).
    Result<ImageRGBA> read_output();
    Result<ImageRGBA> read_accumulation();
    // The active floor's own target after its effects, as the last frame left it. Whole only
    // with a view that reads the floor target (set_view(OutputView::FloorRgb)), which makes
    // the frame clear and draw the active floor's whole target; InvalidInput otherwise.
    Result<ImageRGBA> read_active_floor();

    // What set_effect_ref did.
    enum class EffectChange {
        Values,     // the same graph: the new values reach the next frame through its uniforms
        Rebuilt,    // another graph: this effect alone was built again (pipelines from the pool)
        NeedsLoad,  // another graph that changes what the load planned around it (coverage,
                    // reach, whether it runs at all): nothing changed; load the scene again
    };
    // Live parameters (compositor_params.cpp): gives effect `index` of floor `floor` (empty: of
    // the global effects), counted in the scene's own list, the entry `ref` (the scene's entry
    // with other params or another preset). Its build() runs again. Refusals (no such effect, a
    // parameter refused, build() failing, its passes failing to compile) name the scene file
    // and the effect's field and change nothing.
    Result<EffectChange> set_effect_ref(std::optional<uint32_t> floor, uint32_t index,
                                        const EffectRef& ref);
    // The scene's entry of that effect as it stands; refused (naming the file and field) when
    // the floor or the effect does not exist.
    Result<EffectRef> effect_ref(std::optional<uint32_t> floor, uint32_t index) const;
    const SceneDesc& scene() const { return scene_; }
    const std::vector<LeftOutEntry>& left_out() const { return left_out_; }

    // The camera (compositor_camera.cpp): later frames show `view`, a region of the scene at a
    // scale, in an output of view.width x view.height. A move at the same scale and size plans
    // the floors again and resamples the floors' masks (no allocation, no build()); another
    // scale runs every effect's build() again (an effect whose passes change is rebuilt, its
    // pipelines from the pool); another size also allocates the targets again. Refused, with
    // nothing changed, for a plugin built before ABI 1.2 (unless `view` is the whole canvas at
    // scale 1), an output over the device limit, or a failing build().
    Result<void> set_view_transform(const ViewTransform& view);
    const ViewTransform& view_transform() const { return view_; }

    uint32_t floor_count() const { return uint32_t(resources_->floors().size()); }
    uint32_t width() const { return width_; }  // the output: the camera's, else the canvas
    uint32_t height() const { return height_; }
    const LoadStats& load_stats() const { return load_stats_; }
    // Whether some floor effect declared a reach (set_reach) that limits what is shaded.
    bool declares_reach() const;
    // Effect passes of every instance (floors and global), by how they were given.
    EffectPassCounts effect_pass_counts() const;
    const FramePlan& last_plan() const { return last_plan_; }
    // Frames compiled so far (frame_for): at load, then only for a new shape or after the
    // camera moved or an effect was rebuilt.
    uint64_t frames_compiled() const { return frames_compiled_; }
    // The fewest pixels any renderer of floors 0..active_floor must shade (what
    // FrameStats::pixels_shaded is judged against): the output over the canvas; each visible
    // floor's tiles once each; for a floor with effects, each full-resolution effect pass and
    // the composite over the exact union of its tiles' pixels (grown by the declared reach of
    // expanding effects), instanced passes over their quads, passes into an effect's own
    // targets at those targets' size; global passes likewise. Floors hidden under opaque
    // floors above count nothing. Bounding-box scissors and clears are what it leaves out.
    uint64_t necessary_pixels(uint32_t active_floor) const;
    // Why frames are not timed although gpu_timings was asked for ("" when they are).
    const std::string& gpu_timings_warning() const { return timer_warning_; }
    // Render targets held (accumulation, output, floor target and stencil when needed).
    std::vector<TargetInfo> targets_held() const;
    // Every GPU image held, targets and scene textures and masks alike.
    std::vector<TargetInfo> images_held() const;

  private:
    Compositor(Renderer& renderer);
    // Load (compositor_load.cpp).
    // Builds every effect instance; returns the mask composites it made (for the GPU upload).
    Result<SceneMasks> create_effects(const SceneDesc& scene);
    // Whether an effect that failed with `error` is left out (recorded) rather than failing.
    bool leave_out(const Error& error, std::optional<uint32_t> floor, size_t index,
                   const EffectRef& ref);
    // Where a floor with coverage-expanding effects may change pixels (see create_effects).
    PixelRect expansion_area(const SceneDesc& scene, size_t floor) const;
    FrameTargetNeeds target_needs() const;
    Result<void> ensure_host_pipelines();
    void plan_geometry(const SceneDesc& scene);
    void create_timer();
    // Resolves an instance's mask inputs to the images a frame binds: its floor's composite of
    // each kind, or the scene-size transparent mask where the floor has none; a global effect
    // (no floor) reads no floor's masks, only the renderer's blank texture.
    void bind_masks(EffectInstance& instance, std::optional<uint32_t> floor) const;
    // compositor_warm_up.cpp
    Result<void> warm_pipelines();
    // compositor_camera.cpp
    // Every effect instance built again for view_ (new_targets: into those targets, all of
    // them; otherwise only those whose passes changed), swapped in only when all succeed.
    Result<void> rebuild_for_view(FrameTargets* new_targets);
    // The floors' masks in render pixels for view_ (allocated at its size when needed, then
    // drawn from the scene-space ones), and every instance bound to them; without a camera the
    // scene-space masks themselves.
    Result<void> view_masks();
    // What the effects of a frame are given besides their images: the time, the output and
    // canvas sizes, the camera, the timer.
    EffectIo effect_io(double time) const;
    // The sampler a tile is drawn with under the current camera.
    VkSampler tile_sampler(const LoadedTile& tile) const;

    // A frame's passes (floor_recording.cpp), compiled once per frame shape and kept.
    struct FrameShape {
        FramePlan plan;
        CompiledFrame frame;
        GpuImage* final_accumulation = nullptr;  // the composite the output reads
        GpuImage* viewed_floor = nullptr;        // the active floor's content, for views
    };
    // What a compiled frame depends on besides the loaded scene and its camera: a change of
    // either drops every compiled frame (invalidate_frames).
    struct FrameKey {
        uint32_t active_floor = 0;
        OutputView view = OutputView::Normal;
        bool effects_enabled = true;
        uint32_t floor_effects_run = 0, global_effects_run = 0;
        auto operator<=>(const FrameKey&) const = default;
    };
    // The compiled frame for floors 0..active_floor as the compositor stands (compositor.cpp):
    // planned and compiled on first use, then kept until invalidate_frames().
    Result<const FrameShape*> frame_for(uint32_t active_floor);
    void invalidate_frames() { frames_.clear(); }
    // A frame's passes over the images `roles` gives the shared roles, not yet compiled.
    struct FrameBuild {
        FrameBuilder builder;
        std::vector<FloorFrameReport> reports;
        std::optional<FloorFrameReport> global;
        GpuImage* final_accumulation = nullptr;
        GpuImage* viewed_floor = nullptr;
        std::vector<const GpuImage*> read_after;  // read after the frame (nulls ignored)
    };
    FrameBuild build_frame(const FramePlan& plan, uint32_t active_floor, const RoleImages& roles);
    // The frame built once to learn when each role is used, then again over the shared images
    // those spans allow, and compiled.
    Result<FrameShape> compile_frame(const FramePlan& plan, uint32_t active_floor);
    // Steps [first, end): floors drawn directly (and skipped ones), in one rendering pass.
    void add_floors_direct(FrameBuilder& frame, const std::vector<FloorStep>& steps, size_t first,
                           size_t end, std::vector<FloorFrameReport>& reports);
    // Tiles with the stencil, the floor's effects, its composite; returns the floor's image
    // after its effects.
    GpuImage* add_floor_through_target(FrameBuilder& frame, const FloorStep& step, bool clear_all,
                                       ReportIndex report, const RoleImages& roles);
    // One chain of effects, a floor's or the global ones: `run` effects in scene order, each
    // reading the image the one before it wrote (the first reads `current`) and writing the
    // other image of the pair, which starts transparent; returns the image the last one wrote.
    // An effect writes "result" within `scissor` (within `rects` when given), or within
    // `expanded` when it, or the whole chain, expands coverage.
    struct EffectChain {
        const std::vector<std::unique_ptr<EffectInstance>>* effects = nullptr;
        size_t run = 0;
        GpuImage* current = nullptr;
        GpuImage* next = nullptr;
        PixelRect scissor, expanded;
        bool expanding = false;
        const std::vector<PixelRect>* rects = nullptr;
        ReportIndex report = 0;  // where its passes count
        std::string name;        // "floor 2", "global": names its clear pass
    };
    GpuImage* add_effect_chain(FrameBuilder& frame, const EffectChain& chain);
    // One effect's passes, each naming the images it reads and writes: `previous` and `result`
    // as its chain gives them, "result" drawn within `scissor` (within `rects` when given). The
    // warm-up's shade one pixel each and are sinks (nothing reads what they draw).
    struct EffectPasses {
        EffectInstance* effect = nullptr;
        GpuImage* previous = nullptr;
        GpuImage* result = nullptr;
        PixelRect scissor;
        const std::vector<PixelRect>* rects = nullptr;
        ReportIndex report = 0;
        bool warm_up = false;
    };
    void add_effect_passes(FrameBuilder& frame, const EffectPasses& at);
    // The global effects on the composite (their report made when any runs); returns the
    // composite after them.
    GpuImage* add_global_effects(FrameBuilder& frame, std::optional<FloorFrameReport>& global,
                                 const RoleImages& roles);
    void add_output(FrameBuilder& frame, GpuImage& accumulation, GpuImage* floor_image);
    void record_injection(VkCommandBuffer cmd, const PixelRect& scissor, FloorFrameReport& report);
    void record_composite(VkCommandBuffer cmd, const FloorStep& step, GpuImage& floor,
                          const PixelRect& area, const std::vector<PixelRect>* rects,
                          bool expanding, FloorFrameReport& report);
    void draw_tiles(VkCommandBuffer cmd, HostPass pass, uint32_t floor, const PixelRect& scissor,
                    FloorFrameReport& report);
    // Binds the pass's pipeline (its isolation variant in that view) and its two images.
    void bind(VkCommandBuffer cmd, HostPass pass, VkImageView primary, VkImageView secondary,
              VkSampler sampler);
    void set_scissor(VkCommandBuffer cmd, const PixelRect& rect);
    bool expands(uint32_t floor) const;  // some effect of the floor expands its coverage
    HostPass inject_pass() const;

    Renderer& renderer_;
    VulkanContext& context_;
    CompositorOptions options_;
    SceneDesc scene_;
    uint32_t width_ = 0, height_ = 0;  // the output (view_.width, view_.height)
    ViewTransform view_;               // the camera; ViewTransform::whole without one
    std::unique_ptr<SceneResources> resources_;
    HostPipelines* pipelines_ = nullptr;  // owned by the renderer, shared by scenes
    std::vector<std::vector<std::unique_ptr<EffectInstance>>> floor_effects_;  // per floor
    std::vector<std::unique_ptr<EffectInstance>> global_effects_;
    FrameTargets targets_;
    GpuImage* final_accumulation_ = nullptr;  // what the output read last frame
    GpuImage* viewed_floor_ = nullptr;        // the active floor's content, for views
    std::map<FrameKey, FrameShape> frames_;   // compiled frames (frame_for)
    uint64_t frames_compiled_ = 0;
    std::vector<FloorGeometry> geometry_;  // what the planner works from, in render pixels
    // Per floor, per tile: the render pixels it shades under the camera.
    std::vector<std::vector<PixelRect>> tile_pixels_;
    std::vector<PixelRect> expansion_areas_;  // per floor; empty unless it has expanding effects
    // Per floor with effects that do not expand: the union of its tiles' pixels as disjoint
    // rects, where its "result" passes and its composite draw (one draw each), so tiles far
    // apart do not shade their whole bounding box. Empty: draw over the floor's scissor.
    std::vector<std::vector<PixelRect>> shading_rects_;
    LoadStats load_stats_;
    FramePlan last_plan_;
    std::unique_ptr<GpuTimer> timer_;  // only with CompositorOptions::gpu_timings
    std::string timer_warning_;
    bool effects_enabled_ = true;
    uint32_t global_effects_run_ = UINT32_MAX;  // how many of global_effects_ run
    uint32_t floor_effects_run_ = UINT32_MAX;   // how many of each floor's effects run
    // The floors' mask composites for build() when set_effect_ref runs it again: composited
    // from the files on the first such call that needs them, then kept (a load keeps none).
    std::optional<SceneMasks> live_masks_;
    std::vector<LeftOutEntry> left_out_;
    // The floors' masks in render pixels while a camera is set (kind -> image, per floor), and
    // a transparent one for floors without a kind; empty without a camera.
    std::vector<std::map<std::string, GpuImage>> view_masks_;
    std::optional<GpuImage> view_blank_mask_;
};

}  // namespace acetate
