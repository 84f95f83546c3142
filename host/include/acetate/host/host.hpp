#pragma once
// The Acetate host, embedded in another program (docs/embedding.md). A Host owns a Vulkan
// device, the plugin loader and the pipelines; a Scene is one scene loaded on it, with its
// floors, images and render targets. Rendering a frame allocates, loads and compiles nothing:
// everything a scene needs is created when it is loaded.
//
//     auto host = acetate::host::Host::create({});
//     auto scene = (*host)->load_scene_file("harbour/scene.json");
//     (*scene)->set_active_floor(1);
//     (*scene)->set_time(2.5);
//     auto stats = (*scene)->render();
//     (*scene)->write_frame("frame.png");
//
// The load policy is part of the host, not of a program built on it: a scene loads a plugin
// only when the validation registry holds it VALIDATED for exactly that binary (SHA-256), every
// sign-off verified against the maintainers' keys (docs/registry.md, "Host policy"), unless
// HostOptions::allow_unvalidated says otherwise. A refused plugin fails the scene's load with
// the same line `acetate render` prints; its code never runs in the process.
//
// Errors are Result values (acetate/host/result.hpp) with one-line messages; nothing here
// throws. A Host and its Scenes may be called from several threads: the calls that touch the
// device or a scene take one lock per Host and run one after another (a load on one thread
// waits for a frame on another). Scenes of different Hosts do not wait for each other.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "acetate/host/result.hpp"

namespace acetate::host {

struct HostOptions {
    // The device: an index ("1") or a case-insensitive name substring ("llvmpipe"). Empty:
    // $ACETATE_DEVICE, else the first discrete GPU, then integrated, virtual, CPU (lavapipe).
    std::string device;
    // The Khronos validation layer. A frame during which it reports anything fails render().
    // Off by default, or on with $ACETATE_VALIDATION=1.
    bool validation = false;
    // Keeps compiled pipelines between runs in the user's cache folder
    // ($XDG_CACHE_HOME/acetate), written by save_pipeline_cache().
    bool pipeline_cache = true;
    // Searched for plugins before $ACETATE_PLUGIN_PATH and the installation's lib/acetate/plugins.
    std::vector<std::filesystem::path> plugin_directories;

    // The load policy. The registry file: else $ACETATE_REGISTRY, else the user's
    // ($XDG_DATA_HOME/acetate/registry.json). The maintainers' keys: else
    // $ACETATE_ALLOWED_SIGNERS, else the installation's share/acetate/validation/allowed_signers.
    std::optional<std::filesystem::path> registry;
    std::optional<std::filesystem::path> allowed_signers;
    // Loads plugins the registry does not hold VALIDATED, each with one warning. For
    // development only: nothing vouches for what such a plugin does.
    bool allow_unvalidated = false;
    // How a refusal tells the user to load the plugin anyway (after "or "): a program names
    // its own switch here ("pass --allow-unvalidated").
    std::string allow_unvalidated_hint = "set HostOptions::allow_unvalidated";
    // False: no plugin is loaded at all and the registry is not read (a malformed registry
    // then does not matter); a scene naming a plugin fails to load, naming its field.
    bool load_plugins = true;
    // Where warnings go, one line each (no newline); default: standard error.
    std::function<void(const std::string&)> on_warning;
};

// What a scene's frame shows: the picture, or a debug view of its floors (docs/design.md,
// L-debug-views).
enum class View {
    Normal,      // the composite over the canvas background
    FloorAlpha,  // the active floor's own alpha, grey
    AccumAlpha,  // the composite's alpha, grey
    FloorRgb,    // the active floor's colour with alpha forced to 1
    Violations,  // red where the active floor has colour at alpha 0 (or NaN/Inf)
    Isolation,   // each floor tinted its own colour
};
// The view named "normal", "floor-alpha", "accum-alpha", "floor-rgb", "violations" or
// "isolation"; any other name fails, listing these.
Result<View> parse_view(const std::string& name);
const char* view_name(View view);

// The format of a scene's targets and textures: RGBA in 16-bit or 32-bit float.
enum class Precision { Float16, Float32 };

// How a scene is loaded. The defaults give the picture at half-float precision.
struct SceneOptions {
    View view = View::Normal;
    Precision precision = Precision::Float16;
    // An effect whose plugin the load policy refuses (ErrorCode::PluginRefused) fails the
    // load; with this set, the scene loads without that effect instead, as if its file did not
    // list it, and Scene::left_out_effects() says which and why (each also goes to
    // on_warning). Any other failure still fails the load.
    bool leave_out_refused_effects = false;
    // Time every step of each frame on the GPU (Vulkan timestamp queries around each floor's
    // tiles, each effect pass, the composite and the output): FrameStatistics::gpu_passes.
    // Costs two timestamps a step. A device whose queue cannot time renders untimed, and
    // Scene::gpu_timings_warning() says why.
    bool gpu_timings = false;
};

// A scene file read and checked without a device (Host::inspect_scene_file): enough for a
// program to check its own arguments, and what it may not overwrite, before it starts one.
struct SceneInfo {
    std::filesystem::path file;
    uint32_t width = 0, height = 0;
    std::vector<std::string> floor_names;  // bottom to top
    uint32_t active_floor = 0;             // the scene's own
    bool names_plugins = false;            // some floor or global effect names a plugin
    // The plugin id of each effect entry, as listed: per floor, and the global effects (what an
    // EffectSlot counts).
    std::vector<std::vector<std::string>> floor_effects;
    std::vector<std::string> global_effects;
    // Every file loading it reads, with the field naming it ("scene.json: floors[0].tiles[1]
    // .image", "....masks.water"); the scene file itself first, named "scene".
    struct Input {
        std::filesystem::path file;
        std::string field;
    };
    std::vector<Input> inputs;
};

// A frame read back: premultiplied, linear RGBA, 32-bit float, rows top to bottom.
struct Image {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;  // width * height * 4
};

struct LoadStatistics {
    double milliseconds = 0;
    uint64_t images_loaded = 0, targets_allocated = 0, shaders_compiled = 0, pipelines_created = 0;
    // Tile texels with colour at alpha 0 (or NaN/Inf): dropped when drawn, and warned about.
    uint64_t tile_texel_violations = 0;
};

// One step of a frame: a floor, or the global effects on the composite.
struct StepStatistics {
    uint32_t floor = 0;  // UINT32_MAX for the global effects
    std::string path;    // "skipped", "direct", "through-target" or "global"
    std::string why;     // why the frame's plan chose that path
    int64_t x = 0, y = 0, width = 0, height = 0;  // the scissor, output pixels
    uint32_t passes = 0;
    uint64_t pixels_shaded = 0;
    uint64_t violations = 0;
};

// A render target or texture a loaded scene holds on the device.
struct ImageInfo {
    std::string name;    // "accumulation", "transient.0", "acetate.bloom.down1", a tile's file
    std::string format;  // "rgba16f", ...
    uint32_t width = 0, height = 0;
    uint64_t bytes = 0;
};

// One effect of a scene, as its file lists it: the `index`-th entry of floor `floor`'s
// "effects", or of "global_effects" when `floor` is empty.
struct EffectSlot {
    std::optional<uint32_t> floor;
    uint32_t index = 0;
};

// What a live change of an effect's parameters cost. Values that the effect's build() turns
// into the same passes reach the next frame with nothing rebuilt. Values that change its
// passes (a bloom's number of levels) rebuild that effect alone, and `rebuilt` says so: its
// shaders compiled unless the host compiled them before, no image decoded, the other effects
// untouched. Only a change the floor's targets were chosen for (the effect starts or stops
// growing coverage, or declares nothing) loads the scene again: `reloaded`.
struct ParamChange {
    bool rebuilt = false;
    bool reloaded = false;
    double milliseconds = 0;
    // What the change did on the device (as LoadStatistics counts it).
    uint64_t images_loaded = 0, targets_allocated = 0, shaders_compiled = 0, pipelines_created = 0;
};

// What a frame shows: the scene's region from (x, y), `width` x `height` scene pixels, at
// `scale` output pixels per scene pixel, in an output of round(width * scale) x
// round(height * scale) pixels (read_frame()'s size). A program that keeps its window's size
// while it zooms sets width = window width / scale. The region may reach past the canvas,
// where the frame shows the background. Without set_camera: the whole canvas at scale 1.
struct Camera {
    double x = 0, y = 0;           // the region's top-left corner, scene pixels
    double width = 0, height = 0;  // the region's size, scene pixels
    double scale = 1;              // output pixels per scene pixel, 1/64 to 64
};
// What a camera change cost. A move at the same scale and output size changes numbers the
// frame reads and resamples the floors' masks (if effects read any): nothing is built, loaded,
// allocated or compiled. Another scale runs every effect's build() again, told the new scale
// (`rebuilt`): an effect whose passes change is rebuilt, its pipelines from the Host's pool.
// Another output size (`resized`) also allocates the render targets again.
struct CameraChange {
    bool rebuilt = false;
    bool resized = false;
    double milliseconds = 0;
    uint64_t images_loaded = 0, targets_allocated = 0, shaders_compiled = 0, pipelines_created = 0;
};
// The GPU time of one step of a frame (SceneOptions::gpu_timings).
struct PassTime {
    std::string name;  // "floor 0 tiles", an effect pass ("floor0.acetate.water.shade"), "output"
    double milliseconds = 0;
};

struct FrameStatistics {
    uint32_t active_floor = 0;
    double time = 0;             // seconds, as the effects saw it
    double milliseconds = 0;     // record, submit and wait
    uint32_t passes = 0;         // draws recorded
    uint64_t pixels_shaded = 0;  // sum over passes of their area
    uint64_t violations = 0;     // pixels reaching the composite with colour at alpha 0, or NaN
    // Work done during the frame: 0 for all four, always (everything is made at load).
    uint64_t images_loaded = 0, targets_allocated = 0, shaders_compiled = 0, pipelines_created = 0;
    // Pipeline barriers recorded: each image layout transition, and one that makes the frame's
    // writes visible to the host. The same for every frame of one plan.
    uint64_t barriers = 0;
    std::vector<StepStatistics> floors;            // floors 0..active_floor, bottom to top
    std::optional<StepStatistics> global_effects;  // when the scene has any
    std::vector<PassTime> gpu_passes;  // in the order recorded; with SceneOptions::gpu_timings
};

// An effect a scene loaded without (SceneOptions::leave_out_refused_effects).
struct LeftOutEffect {
    EffectSlot slot;
    std::string plugin;   // its id
    std::string message;  // why, the line the load would have failed with
};

// What Host::reload_plugins() found for one plugin the Host has loaded.
struct PluginReload {
    std::string plugin;  // its id
    std::filesystem::path file;
    bool changed = false;         // the file's bytes differ from those loaded
    uint32_t scenes_rebuilt = 0;  // scenes of this Host loaded again with the new code
    // Why the changed file, or a scene with it, was not taken: the policy's refusal, a broken
    // or missing file, a scene's load error. "" when everything took it.
    std::string refused;
};

class Scene;

class Host {
  public:
    // Starts Vulkan on the chosen device and reads the load policy's registry (a missing file
    // means nothing is VALIDATED; a malformed one is an error naming the file and field).
    // Fails when no device matches, the device lacks what Acetate needs, or the registry is bad.
    static Result<std::unique_ptr<Host>> create(const HostOptions& options);
    ~Host();
    Host(const Host&) = delete;
    Host& operator=(const Host&) = delete;

    // The device in use, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    std::string device_name() const;

    // The files the load policy reads for these options (whether or not they exist): what a
    // program must not overwrite. Neither needs a Host.
    static std::filesystem::path registry_file(const HostOptions& options);
    static std::filesystem::path allowed_signers_file(const HostOptions& options);
    // Reads and checks a scene file as load_scene_file does, without a device: its errors are
    // the same lines. Loads no image and no plugin.
    static Result<SceneInfo> inspect_scene_file(const std::filesystem::path& file);

    // Loads a scene file (docs/scene-format.md): its plugins (each through the load policy),
    // images and masks; allocates its targets; compiles and warms every pipeline. Errors name
    // the file and the JSON field, or the plugin and why it was refused.
    Result<std::unique_ptr<Scene>> load_scene_file(const std::filesystem::path& file,
                                                   const SceneOptions& options = {});
    // The same from a description in memory: `json` is the scene file's text; relative image
    // paths are taken from `base_directory`; messages name the scene `name`.
    Result<std::unique_ptr<Scene>> load_scene_text(const std::string& json,
                                                   const std::filesystem::path& base_directory,
                                                   const std::string& name = "scene.json",
                                                   const SceneOptions& options = {});

    // A plugin rebuilt on disk: checks every plugin file this Host has loaded against the
    // bytes it loaded (SHA-256, one hash per plugin). A changed file goes through the load
    // policy again; once admitted it serves every later load, and each scene of this Host that
    // uses the plugin is loaded again with it (its active floor, time and live parameters
    // kept; its next frame is the new code's). A refused, missing or broken file, or a scene
    // that fails to load with the new code, leaves the old code rendering that scene, and the
    // outcome says why. One outcome per loaded plugin.
    std::vector<PluginReload> reload_plugins();

    // Writes the pipeline cache (with HostOptions::pipeline_cache), atomically.
    Result<void> save_pipeline_cache();
    // Why the pipeline cache file was not used at start-up ("" when it was, or is off).
    std::string pipeline_cache_warning() const;
    // Plugins loaded so far (each once per process, shared by every scene) and pipelines made.
    uint32_t plugins_loaded() const;
    uint32_t pipelines_in_pool() const;
    // Messages the Vulkan validation layer has reported since create() (with validation on).
    uint32_t validation_messages() const;

    struct State;  // what a Host and its Scenes share

  private:
    explicit Host(std::shared_ptr<State> state);
    std::shared_ptr<State> state_;
};

// A scene loaded on a Host. It keeps what it needs of the Host alive, so either may be
// destroyed first.
class Scene {
  public:
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    uint32_t width() const;  // the canvas, in scene pixels (the frame's size is the camera's)
    uint32_t height() const;
    uint32_t floor_count() const;
    std::string floor_name(uint32_t floor) const;  // "" for a floor out of range

    // The floor the user is on: floors above it are not drawn. Starts at the scene's
    // active_floor. Fails for a floor out of range, naming the scene and the floors it has.
    Result<void> set_active_floor(uint32_t floor);
    uint32_t active_floor() const;
    // The time effects animate with, in seconds. Fails for a value that is not finite or
    // outside the 32-bit float range (effects read it as a float).
    Result<void> set_time(double seconds);
    double time() const;

    // Live parameters: the next frame renders as the scene file would with these values in
    // the effect's "params" (a scalar has one value; a vector or colour two or three), or
    // with that "preset" ("" for none). Values are clamped to the parameter's range as a
    // file's are. Refusals change nothing and name the scene file, the effect's field and the
    // parameter: no such floor or effect, an unknown parameter or preset, a value that is not
    // finite or has the wrong number of components, or build() failing with the values.
    Result<ParamChange> set_param(const EffectSlot& effect, const std::string& name,
                                  const std::vector<float>& value);
    Result<ParamChange> set_preset(const EffectSlot& effect, const std::string& preset);

    // The camera for later frames (see Camera, CameraChange). Refused, with nothing changed,
    // naming the scene and the field or plugin: a number out of its range (each named), an
    // output larger than the device allows, an effect whose plugin was built against ABI 1.0
    // or 1.1 (they know no camera: such a scene renders only the whole canvas at scale 1), or
    // an effect's build() failing at the new scale. Floors, tiles and masks outside the region
    // cost nothing; its live parameters, time and active floor are kept.
    Result<CameraChange> set_camera(const Camera& camera);
    Camera camera() const;
    // Renders floors 0..active_floor, their effects, the composite and the global effects.
    // Allocates nothing. Fails on a device error, or with validation on, on a validation
    // message during the frame.
    Result<FrameStatistics> render();
    // The last frame rendered (render() first): the composite over the canvas background.
    Result<Image> read_frame();
    // read_frame() written to `file`: .exr (half float, premultiplied linear) or .png (8-bit
    // sRGB), atomically: the file is the old one or the new one, never half written.
    Result<void> write_frame(const std::filesystem::path& file);

    const LoadStatistics& load_statistics() const;
    // The effects left out because the policy refused their plugin; empty unless
    // SceneOptions::leave_out_refused_effects was set.
    std::vector<LeftOutEffect> left_out_effects() const;
    // Why frames are not timed although SceneOptions::gpu_timings asked for it ("" when they
    // are, or when it was not asked).
    std::string gpu_timings_warning() const;
    // What the scene holds on the device: its render targets, and every image (targets, tile
    // textures and masks).
    std::vector<ImageInfo> render_targets() const;
    std::vector<ImageInfo> images_held() const;

    struct Loaded;  // the loaded scene behind it

  private:
    friend class Host;
    explicit Scene(std::unique_ptr<Loaded> loaded);
    std::unique_ptr<Loaded> loaded_;
};

}  // namespace acetate::host
