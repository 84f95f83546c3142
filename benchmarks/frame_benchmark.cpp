// Frame benchmarks for the floor compositor (docs/performance.md).
//
//   frame/...      frame time of Compositor::render vs floor count and canvas size
//   overhead/...   Compositor::render vs a hand-written recording of the same draws, interleaved
//   optim/...      the frame planner's optimisations on vs off, interleaved
//
// Every frame is timed around Compositor::render (plan + record + submit + fence wait) with a
// steady clock and handed to Google Benchmark as manual time. Each compositor renders a few
// warm-up frames before timing (lavapipe compiles shader variants at first use). Validation
// layers are off. After the run a summary with per-frame medians is printed as Markdown tables.
//
// Scenes are built in code: tile images are generated, written as EXR into a scratch folder
// and loaded by the host like any scene.

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/compositor.hpp"
#include "render/host_pipelines.hpp"
#include "render/renderer.hpp"
#include "render/scene_resources.hpp"
#include "scene/image_io.hpp"
#include "scene/scene.hpp"
#include "vulkan/gpu_image.hpp"
#include "vulkan/vulkan_context.hpp"

namespace {

using namespace acetate;
using Clock = std::chrono::steady_clock;

constexpr int kWarmupFrames = 3;

[[noreturn]] void die(const std::string& what) {
    std::fprintf(stderr, "acetate_frame_benchmark: %s\n", what.c_str());
    std::exit(1);
}

template <class T>
T must(Result<T> r, const char* what) {
    if (!r) die(fmt::format("{}: {}", what, r.error().message));
    return std::move(r.value());
}

void must(Result<void> r, const char* what) {
    if (!r) die(fmt::format("{}: {}", what, r.error().message));
}

void vk_check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) die(fmt::format("{} failed (VkResult {})", what, int(r)));
}

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// ---------------------------------------------------------------------------------------------
// Process-wide state

std::unique_ptr<VulkanContext> g_context;
// Process-wide pipelines and plugin loader; no disk pipeline cache, no plugin directories (the
// benchmark scenes have no effects).
std::unique_ptr<Renderer> g_renderer;
std::filesystem::path g_scratch;

VulkanContext& context() {
    return *g_context;
}
Renderer& renderer() {
    return *g_renderer;
}

// ---------------------------------------------------------------------------------------------
// Scenes built in code

// A premultiplied tile image: blocks of partial alpha (0.35..0.8) with fully transparent gaps
// (about one block in six), or alpha 1 everywhere when `opaque`. Different `seed`s give
// different colours and gap positions.
ImageRGBA make_tile_image(uint32_t w, uint32_t h, uint32_t seed, bool opaque) {
    ImageRGBA image(w, h);
    const uint32_t block = std::max<uint32_t>(8, std::min(w, h) / 16);
    const float hue[3] = {0.3f + 0.6f * float((seed * 37) % 10) / 10.0f,
                          0.3f + 0.6f * float((seed * 53 + 3) % 10) / 10.0f,
                          0.3f + 0.6f * float((seed * 71 + 7) % 10) / 10.0f};
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            const uint32_t bx = x / block, by = y / block;
            float a = 1.0f;
            if (!opaque) {
                if ((bx * 7 + by * 3 + seed) % 6 == 0)
                    a = 0.0f;
                else
                    a = 0.35f + 0.05f * float((bx * 13 + by * 29 + seed * 5) % 10);
            }
            const float shade = 0.5f + 0.5f * float(x) / float(w);
            float* p = image.at(x, y);
            for (int c = 0; c < 3; ++c) p[c] = hue[c] * shade * a;
            p[3] = a;
        }
    }
    return image;
}

// Writes the image once per run (same size, seed and opacity: same file).
std::filesystem::path tile_file(uint32_t w, uint32_t h, uint32_t seed, bool opaque) {
    const auto path =
        g_scratch / fmt::format("tile_{}x{}_{}{}.exr", w, h, seed, opaque ? "_opaque" : "");
    if (!std::filesystem::exists(path))
        must(save_image(path, make_tile_image(w, h, seed, opaque)), "writing a tile image");
    return path;
}

SceneDesc empty_scene(uint32_t width, uint32_t height) {
    SceneDesc scene;
    scene.file = g_scratch / "scene.json";  // named in messages only
    scene.width = width;
    scene.height = height;
    scene.background = {0.05f, 0.05f, 0.06f, 1.0f};
    return scene;
}

void add_tile(SceneDesc& scene, const std::filesystem::path& image, SceneRect rect) {
    FloorDesc floor;
    floor.name = fmt::format("floor{}", scene.floors.size());
    floor.tiles.push_back({image, rect, {}});
    scene.floors.push_back(floor);
    scene.active_floor = uint32_t(scene.floors.size() - 1);
}

// `floors` floors, each one tile covering 81% of the canvas (90% of each side) at a different
// whole-pixel offset, partial alpha with transparent gaps, so no floor hides another.
// scaled = false: the image is the rect's size (drawn 1:1, texelFetch);
// scaled = true: the image is half the rect's size per side (drawn x2, bilinear).
struct FloorScene {
    uint32_t width = 1920, height = 1080, floors = 4;
    bool scaled = false;
    std::string key() const {
        return fmt::format("{}x{}/floors:{}/{}", width, height, floors, scaled ? "x2" : "1to1");
    }
};

SceneDesc make_floor_scene(const FloorScene& spec) {
    SceneDesc scene = empty_scene(spec.width, spec.height);
    const uint32_t tw = uint32_t(std::lround(spec.width * 0.9));
    const uint32_t th = uint32_t(std::lround(spec.height * 0.9));
    for (uint32_t f = 0; f < spec.floors; ++f) {
        const uint32_t iw = spec.scaled ? tw / 2 : tw, ih = spec.scaled ? th / 2 : th;
        const double x = double(((f * 3) % 11) * (spec.width - tw) / 10);
        const double y = double(((f * 7) % 11) * (spec.height - th) / 10);
        add_tile(scene, tile_file(iw, ih, f, false), {x, y, double(tw), double(th)});
    }
    return scene;
}

// Four floors at 1920x1080, each covering a tenth of the canvas (608x342 tiles, drawn 1:1);
// floor 2 is opaque and lies exactly over floor 1, which is therefore hidden.
SceneDesc make_tenth_scene() {
    SceneDesc scene = empty_scene(1920, 1080);
    const double w = 608, h = 342;
    add_tile(scene, tile_file(608, 342, 0, false), {100, 100, w, h});   // visible
    add_tile(scene, tile_file(608, 342, 1, false), {1100, 600, w, h});  // hidden by floor 2
    add_tile(scene, tile_file(608, 342, 2, true), {1100, 600, w, h});   // opaque
    add_tile(scene, tile_file(608, 342, 3, false), {450, 300, w, h});   // overlaps floor 0
    return scene;
}

// ---------------------------------------------------------------------------------------------
// Compositors

// Loads and renders kWarmupFrames frames. (Load and first-frame times of a fresh process are
// benchmarks/load_times.sh's business: here pipelines are shared by every scene of the process.)
std::unique_ptr<Compositor> load_warm(const SceneDesc& scene, const CompositorOptions& options) {
    auto compositor = must(Compositor::load(renderer(), scene, options), "Compositor::load");
    for (int i = 0; i < kWarmupFrames; ++i)
        must(compositor->render(scene.active_floor), "warm-up frame");
    return compositor;
}

// Compositors stay loaded for the whole run, so that repetitions of different benchmarks can be
// interleaved (--benchmark_enable_random_interleaving) without reloading.
struct CachedCompositor {
    SceneDesc scene;
    std::unique_ptr<Compositor> compositor;
    double load_ms = 0;
};
std::map<std::string, CachedCompositor> g_cached;

CachedCompositor& cached_compositor(const FloorScene& spec) {
    CachedCompositor& cached = g_cached[spec.key()];
    if (!cached.compositor) {
        cached.scene = make_floor_scene(spec);
        cached.compositor = load_warm(cached.scene, {});
        cached.load_ms = cached.compositor->load_stats().milliseconds;
    }
    return cached;
}

// Times one Compositor::render.
double host_frame(Compositor& compositor, uint32_t active, FrameStats* stats = nullptr) {
    const auto start = Clock::now();
    auto frame = compositor.render(active);
    const double ms = ms_since(start);
    if (!frame) die("Compositor::render: " + frame.error().message);
    if (stats) *stats = std::move(frame.value());
    return ms;
}

// ---------------------------------------------------------------------------------------------
// The raw baseline: the same draws as the compositor's plan, recorded by hand.
//
// The same pipelines (the Renderer's HostPipelines, TileToAccum and Output: the very VkPipelines
// the compositor binds), the same tile images (uploaded by SceneResources from the same files, in
// the same format), targets of the same size, format and usage. One command buffer and fence
// created once and re-recorded every frame; fixed barriers (no layout tracking); no planning, no
// stats. Two shapes:
//   one_pass = true:  clear, one rendering pass over the accumulation with every tile draw (the
//                     scissor set per floor), output pass. The minimum a hand-written renderer
//                     would issue.
//   one_pass = false: clear, one rendering pass per drawn floor with a barrier before each (the
//                     pass structure Compositor records), output pass.
class RawRenderer {
  public:
    RawRenderer(const SceneDesc& scene, const FramePlan& plan, VkFormat format)
        : scene_(scene), plan_(plan), format_(format) {
        VulkanContext& ctx = context();
        for (const FloorStep& step : plan_.steps)
            if (step.path == FloorPath::ThroughTarget)
                die("raw baseline: only floors drawn directly are mirrored");
        resources_ = must(SceneResources::load(ctx, scene, format, {}), "SceneResources::load");
        pipelines_ = &renderer().host_pipelines();
        must(pipelines_->ensure(HostPass::TileToAccum, format), "HostPipelines::ensure");
        must(pipelines_->ensure(HostPass::Output, format), "HostPipelines::ensure");
        const VkImageUsageFlags usage =
            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        accumulation_ = must(GpuImage::create(ctx, "raw.accumulation", scene.width, scene.height,
                                              format, usage, true),
                             "raw accumulation");
        output_ = must(
            GpuImage::create(ctx, "raw.output", scene.width, scene.height, format, usage, true),
            "raw output");
        // Every frame leaves the output as a colour attachment; tell its GpuImage once, so
        // read_output() (read_back_image) starts from the right layout.
        must(ctx.submit_and_wait([&](VkCommandBuffer cmd) {
            output_.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        }),
             "raw output layout");
        VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool.queueFamilyIndex = ctx.queue_family();
        vk_check(vkCreateCommandPool(ctx.device(), &pool, nullptr, &pool_), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = pool_;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        vk_check(vkAllocateCommandBuffers(ctx.device(), &alloc, &cmd_), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vk_check(vkCreateFence(ctx.device(), &fence, nullptr, &fence_), "vkCreateFence");
        for (int i = 0; i < kWarmupFrames; ++i) {
            frame(true);
            frame(false);
        }
    }
    ~RawRenderer() {
        VkDevice device = context().device();
        vkDeviceWaitIdle(device);
        vkDestroyFence(device, fence_, nullptr);
        vkDestroyCommandPool(device, pool_, nullptr);
    }
    RawRenderer(const RawRenderer&) = delete;
    RawRenderer& operator=(const RawRenderer&) = delete;

    // Records, submits and waits for one frame; returns its milliseconds (measured like
    // host_frame: from before recording to after the fence wait).
    double frame(bool one_pass) {
        VulkanContext& ctx = context();
        const auto start = Clock::now();
        vk_check(vkResetCommandPool(ctx.device(), pool_, 0), "vkResetCommandPool");
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vkBeginCommandBuffer(cmd_, &begin);
        record(one_pass);
        vkEndCommandBuffer(cmd_);
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd_;
        vk_check(vkQueueSubmit(ctx.queue(), 1, &submit, fence_), "vkQueueSubmit");
        vk_check(vkWaitForFences(ctx.device(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        vk_check(vkResetFences(ctx.device(), 1, &fence_), "vkResetFences");
        return ms_since(start);
    }

    ImageRGBA read_output() {
        // read_back_image restores the layout it finds; the output is left as an attachment.
        return must(read_back_image(context(), output_), "reading the raw output");
    }

  private:
    // Same full barrier as GpuImage::transition.
    void barrier(VkImage image, VkImageLayout from, VkImageLayout to) {
        VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
        b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = 1;
        dep.pImageMemoryBarriers = &b;
        vkCmdPipelineBarrier2(cmd_, &dep);
    }

    static VkRect2D vk_rect(const PixelRect& r) {
        return {{int32_t(r.x0), int32_t(r.y0)}, {uint32_t(r.x1 - r.x0), uint32_t(r.y1 - r.y0)}};
    }

    void begin_pass(VkImageView view, const PixelRect& area, VkAttachmentLoadOp load) {
        VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        color.imageView = view;
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = load;
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = vk_rect(area);
        info.layerCount = 1;
        info.colorAttachmentCount = 1;
        info.pColorAttachments = &color;
        vkCmdBeginRendering(cmd_, &info);
        const VkViewport viewport{0, 0, float(scene_.width), float(scene_.height), 0, 1};
        vkCmdSetViewport(cmd_, 0, 1, &viewport);
    }

    void push_images(VkImageView primary, VkImageView secondary, VkSampler sampler,
                     uint32_t count) {
        const VkDescriptorImageInfo images[2] = {
            {sampler, primary, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {sampler, secondary, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
        VkWriteDescriptorSet writes[2] = {};
        for (uint32_t i = 0; i < count; ++i) {
            writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
            writes[i].dstBinding = i;
            writes[i].descriptorCount = 1;
            writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            writes[i].pImageInfo = &images[i];
        }
        context().push_descriptor_fn()(cmd_, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_->layout(),
                                       0, count, writes);
    }

    void draw_floor(const FloorStep& step) {
        const VkRect2D scissor = vk_rect(step.scissor);
        vkCmdSetScissor(cmd_, 0, 1, &scissor);
        for (const LoadedTile& tile : resources_->floors()[step.floor].tiles) {
            if (intersect(tile.pixels, step.scissor).empty()) continue;
            // As draw_tiles: a 1:1 tile reads its texels through the nearest sampler.
            const VkSampler sampler = pipelines_->tile_sampler(tile.one_to_one);
            push_images(tile.texture->view(), tile.texture->view(), sampler, 1);
            TilePushConstants pc;
            pc.tile_rect[0] = float(tile.rect.x);
            pc.tile_rect[1] = float(tile.rect.y);
            pc.tile_rect[2] = float(tile.rect.width);
            pc.tile_rect[3] = float(tile.rect.height);
            pc.canvas_size[0] = float(scene_.width);
            pc.canvas_size[1] = float(scene_.height);
            pipelines_->push(cmd_, pc);
            vkCmdDraw(cmd_, 4, 1, 0, 0);
        }
    }

    void record(bool one_pass) {
        const PixelRect all{0, 0, int64_t(scene_.width), int64_t(scene_.height)};
        // The accumulation's old contents are cleared anyway; the output's are overwritten.
        barrier(accumulation_.image(), VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd_, accumulation_.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             &zero, 1, &range);
        if (one_pass) {
            PixelRect area;
            for (const FloorStep& step : plan_.steps)
                if (step.path == FloorPath::Direct) area = bounding_union(area, step.scissor);
            barrier(accumulation_.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
            if (!area.empty()) {
                begin_pass(accumulation_.view(), area, VK_ATTACHMENT_LOAD_OP_LOAD);
                vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                  pipelines_->pipeline(HostPass::TileToAccum, format_));
                for (const FloorStep& step : plan_.steps)
                    if (step.path == FloorPath::Direct) draw_floor(step);
                vkCmdEndRendering(cmd_);
            }
        } else {
            VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
            for (const FloorStep& step : plan_.steps) {
                if (step.path != FloorPath::Direct) continue;
                barrier(accumulation_.image(), layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
                layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
                begin_pass(accumulation_.view(), step.scissor, VK_ATTACHMENT_LOAD_OP_LOAD);
                vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                  pipelines_->pipeline(HostPass::TileToAccum, format_));
                draw_floor(step);
                vkCmdEndRendering(cmd_);
            }
            if (layout != VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL)
                barrier(accumulation_.image(), layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        }
        // Output: accumulation over the background, every pixel.
        barrier(accumulation_.image(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        barrier(output_.image(), VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        begin_pass(output_.view(), all, VK_ATTACHMENT_LOAD_OP_DONT_CARE);
        const VkRect2D scissor = vk_rect(all);
        vkCmdSetScissor(cmd_, 0, 1, &scissor);
        vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_GRAPHICS,
                          pipelines_->pipeline(HostPass::Output, format_));
        push_images(accumulation_.view(), accumulation_.view(), pipelines_->nearest_sampler(), 2);
        OutputPushConstants pc;  // view 0: OutputView::Normal
        std::copy(scene_.background.begin(), scene_.background.end(), pc.background);
        pipelines_->push(cmd_, pc);
        vkCmdDraw(cmd_, 3, 1, 0, 0);
        vkCmdEndRendering(cmd_);
    }

    SceneDesc scene_;
    FramePlan plan_;
    std::unique_ptr<SceneResources> resources_;
    VkFormat format_;
    HostPipelines* pipelines_ = nullptr;
    GpuImage accumulation_, output_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

// ---------------------------------------------------------------------------------------------
// Results kept for the summary printed after the run (per-frame medians over all repetitions)

struct FrameRow {
    std::vector<double> ms;
    uint64_t pixels_shaded = 0;
    uint32_t passes = 0;
    double load_ms = 0;  // Compositor::load: mostly EXR decode and upload
};
std::map<std::string, FrameRow> g_frame_rows;  // by benchmark name, in name order
std::vector<std::string> g_frame_order;

struct OverheadRow {
    std::string scene;
    size_t frames = 0;
    double host_ms = 0, raw_ms = 0, raw_passes_ms = 0;
    uint32_t passes = 0;
    uint64_t pixels_shaded = 0;
};
std::vector<OverheadRow> g_overhead_rows;

struct OptimRow {
    std::string config;
    size_t frames = 0;
    double ms = 0;
    uint64_t pixels_shaded = 0;
    uint32_t passes = 0;
    std::string paths;
};
std::vector<OptimRow> g_optim_rows;

std::string paths_of(const FrameStats& stats) {
    std::string out;
    for (const FloorFrameReport& f : stats.floors) {
        if (!out.empty()) out += ", ";
        out += f.path == "skipped" ? "skip" : f.path == "direct" ? "direct" : "target";
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Benchmarks

// a. Frame time of Compositor::render for one scene.
void bm_frame(benchmark::State& state, FloorScene spec, std::string name) {
    CachedCompositor& cached = cached_compositor(spec);
    Compositor& compositor = *cached.compositor;
    const uint32_t active = spec.floors - 1;
    FrameStats stats;
    double total_ms = 0;
    FrameRow& row = g_frame_rows[name];
    for (auto _ : state) {
        const double ms = host_frame(compositor, active, &stats);
        state.SetIterationTime(ms / 1000.0);
        total_ms += ms;
        row.ms.push_back(ms);
    }
    row.pixels_shaded = stats.pixels_shaded;
    row.passes = stats.passes;
    row.load_ms = cached.load_ms;
    state.counters["pixels_shaded"] = double(stats.pixels_shaded);
    state.counters["passes"] = double(stats.passes);
    state.counters["Mpx_per_s"] =
        double(stats.pixels_shaded) * double(state.iterations()) / (total_ms / 1000.0) / 1e6;
}

// b. Compositor::render vs the raw recording of the same draws, interleaved frame by frame
// (the order rotates each iteration so no variant always runs after the same one).
void bm_overhead(benchmark::State& state, std::string scene_name,
                 std::function<SceneDesc()> make_scene) {
    const SceneDesc scene = make_scene();
    std::unique_ptr<Compositor> compositor = load_warm(scene, {});
    RawRenderer raw(scene, compositor->last_plan(), CompositorOptions{}.format);
    // The baseline must draw the same image, or the comparison means nothing.
    const ImageRGBA host_image = must(compositor->read_output(), "reading the host's output");
    const ImageRGBA raw_image = raw.read_output();
    double max_diff = 0;
    for (size_t i = 0; i < host_image.pixels.size(); ++i)
        max_diff =
            std::max(max_diff, double(std::fabs(host_image.pixels[i] - raw_image.pixels[i])));
    if (max_diff > 1e-3)
        die(fmt::format("raw baseline draws a different image (max difference {})", max_diff));
    std::vector<double> host_ms, raw_ms, raw_passes_ms;
    FrameStats stats;
    uint64_t round = 0;
    for (auto _ : state) {
        double host = 0;
        for (uint64_t k = 0; k < 3; ++k) {
            switch ((round + k) % 3) {
                case 0:
                    host = host_frame(*compositor, scene.active_floor, &stats);
                    break;
                case 1:
                    raw_ms.push_back(raw.frame(true));
                    break;
                case 2:
                    raw_passes_ms.push_back(raw.frame(false));
                    break;
            }
        }
        ++round;
        host_ms.push_back(host);
        state.SetIterationTime(host / 1000.0);
    }
    OverheadRow row{scene_name,         host_ms.size(),        median(host_ms),
                    median(raw_ms),     median(raw_passes_ms), stats.passes,
                    stats.pixels_shaded};
    state.counters["host_ms"] = row.host_ms;
    state.counters["raw_ms"] = row.raw_ms;
    state.counters["raw_passes_ms"] = row.raw_passes_ms;
    state.counters["host_over_raw"] = row.host_ms / row.raw_ms;
    state.counters["host_over_raw_passes"] = row.host_ms / row.raw_passes_ms;
    state.counters["pixels_shaded"] = double(row.pixels_shaded);
    g_overhead_rows.push_back(row);
}

// c. The planner's optimisations on vs off on the "tenth" scene, interleaved.
void bm_optimisations(benchmark::State& state) {
    const SceneDesc scene = make_tenth_scene();
    struct Config {
        std::string name;
        PlanOptions plan;
        std::unique_ptr<Compositor> compositor;
        std::vector<double> ms;
        FrameStats stats;
    };
    std::vector<Config> configs;
    auto add = [&](std::string name, bool scissor, bool cull, bool direct, bool merge = true) {
        PlanOptions plan;
        plan.scissor_to_coverage = scissor;
        plan.cull_hidden_floors = cull;
        plan.draw_direct = direct;
        plan.merge_direct_floors = merge;
        configs.push_back({std::move(name), plan, nullptr, {}, {}});
    };
    add("all on (default)", true, true, true);
    add("scissor_to_coverage off", false, true, true);
    add("cull_hidden_floors off", true, false, true);
    add("merge_direct_floors off", true, true, true, false);
    add("draw_direct off", true, true, false);
    add("draw_direct + scissor_to_coverage off", false, true, false);
    add("all off", false, false, false, false);
    for (Config& c : configs) {
        CompositorOptions options;
        options.plan = c.plan;
        c.compositor = load_warm(scene, options);
    }
    uint64_t round = 0;
    for (auto _ : state) {
        double on_ms = 0;
        for (size_t k = 0; k < configs.size(); ++k) {
            const size_t i = (round + k) % configs.size();
            const double ms =
                host_frame(*configs[i].compositor, scene.active_floor, &configs[i].stats);
            configs[i].ms.push_back(ms);
            if (i == 0) on_ms = ms;
        }
        ++round;
        state.SetIterationTime(on_ms / 1000.0);
    }
    for (const Config& c : configs) {
        g_optim_rows.push_back({c.name, c.ms.size(), median(c.ms), c.stats.pixels_shaded,
                                c.stats.passes, paths_of(c.stats)});
    }
    state.counters["on_ms"] = g_optim_rows[g_optim_rows.size() - configs.size()].ms;
    state.counters["off_ms"] = g_optim_rows.back().ms;
    state.counters["on_pixels_shaded"] =
        double(g_optim_rows[g_optim_rows.size() - configs.size()].pixels_shaded);
    state.counters["off_pixels_shaded"] = double(g_optim_rows.back().pixels_shaded);
}

// ---------------------------------------------------------------------------------------------
// Summary

void print_summary() {
    std::printf("\n## Summary (per-frame medians over all timed frames)\n");
    if (!g_frame_order.empty()) {
        std::printf("\n### Frame time (Compositor::render, default options)\n\n");
        std::printf(
            "| benchmark | frames | median ms | min ms | max ms | passes | pixels shaded "
            "| Mpx/s (median) | load ms |\n"
            "|---|---|---|---|---|---|---|---|---|\n");
        for (const std::string& name : g_frame_order) {
            const FrameRow& row = g_frame_rows[name];
            if (row.ms.empty()) continue;
            const double med = median(row.ms);
            std::printf("| %s | %zu | %.2f | %.2f | %.2f | %u | %llu | %.0f | %.0f |\n",
                        name.c_str(), row.ms.size(), med,
                        *std::min_element(row.ms.begin(), row.ms.end()),
                        *std::max_element(row.ms.begin(), row.ms.end()), row.passes,
                        (unsigned long long)row.pixels_shaded,
                        double(row.pixels_shaded) / (med / 1000.0) / 1e6, row.load_ms);
        }
    }
    if (!g_overhead_rows.empty()) {
        std::printf("\n### Host overhead: Compositor::render vs raw recording (interleaved)\n\n");
        std::printf(
            "| scene | frames each | passes | pixels shaded | host ms | raw ms (one pass) "
            "| raw ms (pass per floor) | host/raw | host/raw per floor |\n"
            "|---|---|---|---|---|---|---|---|---|\n");
        for (const OverheadRow& r : g_overhead_rows)
            std::printf("| %s | %zu | %u | %llu | %.2f | %.2f | %.2f | %.3f | %.3f |\n",
                        r.scene.c_str(), r.frames, r.passes, (unsigned long long)r.pixels_shaded,
                        r.host_ms, r.raw_ms, r.raw_passes_ms, r.host_ms / r.raw_ms,
                        r.host_ms / r.raw_passes_ms);
    }
    if (!g_optim_rows.empty()) {
        std::printf("\n### Optimisations on vs off (tenth scene, interleaved)\n\n");
        const OptimRow& on = g_optim_rows.front();
        std::printf(
            "| plan options | frames | median ms | vs all on | passes | pixels shaded | "
            "floor paths (0..3) |\n|---|---|---|---|---|---|---|\n");
        for (const OptimRow& r : g_optim_rows)
            std::printf("| %s | %zu | %.2f | %.2fx | %u | %llu | %s |\n", r.config.c_str(),
                        r.frames, r.ms, r.ms / on.ms, r.passes, (unsigned long long)r.pixels_shaded,
                        r.paths.c_str());
    }
    std::fflush(stdout);
}

std::string driver_info(VkPhysicalDevice device) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &props);
    return fmt::format("{} {}", driver.driverName, driver.driverInfo);
}

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    ContextOptions options = ContextOptions::from_environment();
    // Benchmarks measure the renderer, not the layers. ACETATE_BENCHMARK_VALIDATION=1 turns them
    // on to check the raw baseline's Vulkan usage (timings are then meaningless).
    const char* check = std::getenv("ACETATE_BENCHMARK_VALIDATION");
    options.validation = check && std::string(check) == "1";
    g_context = must(VulkanContext::create(options), "VulkanContext::create");
    g_renderer = must(Renderer::create(*g_context, RendererOptions{}), "Renderer::create");
    g_scratch = std::filesystem::temp_directory_path() /
                fmt::format("acetate-frame-benchmark-{}", ::getpid());
    std::filesystem::create_directories(g_scratch);
    benchmark::AddCustomContext("device", g_context->device_name());
    benchmark::AddCustomContext("driver", driver_info(g_context->physical_device()));
    benchmark::AddCustomContext("nproc", std::to_string(sysconf(_SC_NPROCESSORS_ONLN)));

    // a. Frame time vs floor count (1080p) and vs canvas size (4 floors); plus one scaled case.
    std::vector<std::pair<std::string, FloorScene>> frame_cases;
    for (uint32_t n : {1u, 2u, 4u, 8u, 16u})
        frame_cases.push_back({"floors", {1920, 1080, n, false}});
    for (auto [w, h] : {std::pair{1280u, 720u}, {1920u, 1080u}, {3840u, 2160u}})
        frame_cases.push_back({"canvas", {w, h, 4, false}});
    frame_cases.push_back({"scaled", {1920, 1080, 4, true}});
    for (const auto& [series, spec] : frame_cases) {
        const std::string name = fmt::format("frame/{}/{}", series, spec.key());
        g_frame_order.push_back(name);
        benchmark::RegisterBenchmark(name.c_str(), bm_frame, spec, name)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->MinTime(0.3)
            ->Repetitions(5)
            ->ReportAggregatesOnly(true);
    }

    // b. Host overhead vs raw passes.
    auto overhead = [](std::string label, std::function<SceneDesc()> make) {
        benchmark::RegisterBenchmark(("overhead/" + label).c_str(), bm_overhead, label, make)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->Iterations(40);
    };
    for (uint32_t n : {1u, 4u, 16u}) {
        const FloorScene spec{1920, 1080, n, false};
        overhead(spec.key(), [spec] { return make_floor_scene(spec); });
    }
    overhead("tenth-scene (1920x1080, 4 floors, 1 hidden)", [] { return make_tenth_scene(); });

    // c. Optimisations on vs off.
    benchmark::RegisterBenchmark("optim/tenth-scene", bm_optimisations)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(20);

    benchmark::RunSpecifiedBenchmarks();
    print_summary();
    int status = 0;
    if (g_context->validation_enabled()) {
        const auto& messages = g_context->validation_messages();
        std::printf("\nvalidation messages: %zu\n", messages.size());
        for (size_t i = 0; i < messages.size() && i < 5; ++i)
            std::printf("  %s\n", messages[i].c_str());
        status = messages.empty() ? 0 : 1;
    }

    g_cached.clear();
    g_renderer.reset();
    g_context.reset();
    std::filesystem::remove_all(g_scratch);
    benchmark::Shutdown();
    return status;
}
