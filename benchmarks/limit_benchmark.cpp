// How close a tiled pixel comes to the cheapest pixel lavapipe can blend (docs/performance.md).
//
//   limit/<case>   one 1920x1080 tile pass against a bare premultiplied-over pass, interleaved
//
// Three passes per case, each a rendering pass over a 1920x1080 RGBA16F accumulation with one
// quad covering it and the premultiplied over blend:
//   host   Compositor::render of a one-floor scene, its "floor 0 tiles" interval from the
//          compositor's own GPU timings (CompositorOptions::gpu_timings);
//   tiled  the same draw recorded by hand: the Renderer's TileToAccum pipeline, the tile texture
//          SceneResources uploaded, the push constants and sampler Compositor::draw_tiles uses;
//   bare   the same quad (tile.vert) with a minimal fragment shader,
//          `color = texelFetch(tile, ivec2(gl_FragCoord.xy), 0)`, reading a 1920x1080 texture of
//          the same format: the floor under any tile pass.
// tiled and bare are timed twice: GPU timestamps around the pass (GpuTimer, the primary figure)
// and wall time of submit + fence wait of a command buffer holding only that pass. The order of
// the three rotates every round. Validation layers are off (ACETATE_BENCHMARK_VALIDATION=1 turns
// them on, to check the recordings; timings are then meaningless). The summary prints medians
// and the ratios tiled/bare and host/bare.

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
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
#include "vulkan/gpu_timer.hpp"
#include "vulkan/graphics_pipeline.hpp"
#include "vulkan/shader_compiler.hpp"
#include "vulkan/vulkan_context.hpp"

namespace {

using namespace acetate;
using Clock = std::chrono::steady_clock;

constexpr uint32_t kWidth = 1920, kHeight = 1080;
constexpr VkFormat kFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr int kWarmupRounds = 3;

[[noreturn]] void die(const std::string& what) {
    std::fprintf(stderr, "acetate_limit_benchmark: %s\n", what.c_str());
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

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::unique_ptr<VulkanContext> g_context;
std::unique_ptr<Renderer> g_renderer;
std::filesystem::path g_scratch;

// ---------------------------------------------------------------------------------------------
// Tile images

enum class Alpha {
    Partial,  // alpha 0.6..1 in blocks, never 0: an "opaque-ish" tile
    Gaps,     // the same, with alpha 0 (and colour 0) in a quarter of the blocks
};

ImageRGBA make_image(uint32_t w, uint32_t h, Alpha alpha) {
    ImageRGBA image(w, h);
    const uint32_t block = 16;
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            const uint32_t bx = x / block, by = y / block;
            float a = 0.6f + 0.05f * float((bx * 13 + by * 29) % 9);
            if (alpha == Alpha::Gaps && (bx + 2 * by) % 4 == 0) a = 0.0f;
            const float shade = 0.3f + 0.6f * float(x) / float(w);
            float* p = image.at(x, y);
            p[0] = 0.9f * shade * a;
            p[1] = 0.5f * a;
            p[2] = (1.0f - shade) * a;
            p[3] = a;
        }
    }
    return image;
}

std::filesystem::path image_file(uint32_t w, uint32_t h, Alpha alpha) {
    const auto path = g_scratch / fmt::format("tile_{}x{}_{}.exr", w, h, int(alpha));
    if (!std::filesystem::exists(path))
        must(save_image(path, make_image(w, h, alpha)), "writing a tile image");
    return path;
}

struct Case {
    std::string name;
    Alpha alpha = Alpha::Partial;
    uint32_t scale = 1;  // the image is canvas / scale per side, drawn x scale (bilinear)
};

SceneDesc make_scene(const Case& c) {
    SceneDesc scene;
    scene.file = g_scratch / "scene.json";  // named in messages only
    scene.width = kWidth;
    scene.height = kHeight;
    scene.background = {0.05f, 0.05f, 0.06f, 1.0f};
    FloorDesc floor;
    floor.name = "floor0";
    floor.tiles.push_back({image_file(kWidth / c.scale, kHeight / c.scale, c.alpha),
                           {0, 0, double(kWidth), double(kHeight)},
                           {}});
    scene.floors.push_back(floor);
    scene.active_floor = 0;
    return scene;
}

// ---------------------------------------------------------------------------------------------
// One command buffer, fence and timestamp pair, re-recorded for every pass timed.

class PassTimer {
  public:
    PassTimer() {
        VulkanContext& ctx = *g_context;
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
        timer_ = must(GpuTimer::create(ctx, 1), "GpuTimer::create");
    }
    ~PassTimer() {
        VkDevice device = g_context->device();
        vkDeviceWaitIdle(device);
        vkDestroyFence(device, fence_, nullptr);
        vkDestroyCommandPool(device, pool_, nullptr);
    }
    PassTimer(const PassTimer&) = delete;
    PassTimer& operator=(const PassTimer&) = delete;

    struct Times {
        double gpu_ms = 0, wall_ms = 0;
    };
    // Records `record` between two timestamps, submits and waits. Wall time runs from the
    // submission to the end of the fence wait (recording is not the pass's cost).
    template <class F>
    Times run(F&& record) {
        VulkanContext& ctx = *g_context;
        vk_check(vkResetCommandPool(ctx.device(), pool_, 0), "vkResetCommandPool");
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vkBeginCommandBuffer(cmd_, &begin);
        timer_->begin(cmd_);
        record(cmd_);
        timer_->mark(cmd_, "pass");
        vkEndCommandBuffer(cmd_);
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd_;
        const auto start = Clock::now();
        vk_check(vkQueueSubmit(ctx.queue(), 1, &submit, fence_), "vkQueueSubmit");
        vk_check(vkWaitForFences(ctx.device(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        Times t;
        t.wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        vk_check(vkResetFences(ctx.device(), 1, &fence_), "vkResetFences");
        t.gpu_ms = must(timer_->read(), "GpuTimer::read").at(0).milliseconds;
        return t;
    }

  private:
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    std::unique_ptr<GpuTimer> timer_;
};

// ---------------------------------------------------------------------------------------------
// The bare pass's pipeline: tile.vert and a one-fetch fragment shader, the host stages' layout,
// the same over blend and format as TileToAccum.

constexpr const char* kBareFragment = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D tile;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
void main() { color = texelFetch(tile, ivec2(gl_FragCoord.xy), 0); }
)";

VkPipeline create_bare_pipeline() {
    VkDevice device = g_context->device();
    auto module = [&](const char* name, ShaderStage stage, std::string_view source) {
        const auto spirv = must(compile_glsl(name, stage, source), "compile_glsl");
        VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        info.codeSize = spirv.size() * sizeof(uint32_t);
        info.pCode = spirv.data();
        VkShaderModule out = VK_NULL_HANDLE;
        vk_check(vkCreateShaderModule(device, &info, nullptr, &out), "vkCreateShaderModule");
        return out;
    };
    GraphicsPipelineDesc desc;
    desc.vertex = module("tile.vert", ShaderStage::Vertex, embedded_shader("tile.vert"));
    desc.fragment = module("bare.frag", ShaderStage::Fragment, kBareFragment);
    desc.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    desc.color_format = kFormat;
    desc.blend = BlendMode::Over;
    desc.layout = g_renderer->host_pipelines().layout();
    VkPipeline pipeline =
        must(create_graphics_pipeline(device, VK_NULL_HANDLE, desc, "bare"), "bare pipeline");
    vkDestroyShaderModule(device, desc.vertex, nullptr);
    vkDestroyShaderModule(device, desc.fragment, nullptr);
    return pipeline;
}

// ---------------------------------------------------------------------------------------------
// One case: its scene loaded by a compositor, the same tile uploaded for the hand recordings,
// the bare pass's texture and an accumulation of its own.

class LimitCase {
  public:
    explicit LimitCase(const Case& c) : scene_(make_scene(c)) {
        VulkanContext& ctx = *g_context;
        CompositorOptions options;
        options.format = kFormat;
        options.gpu_timings = true;
        compositor_ = must(Compositor::load(*g_renderer, scene_, options), "Compositor::load");
        if (!compositor_->gpu_timings_warning().empty())
            die("no GPU timings: " + compositor_->gpu_timings_warning());
        resources_ = must(SceneResources::load(ctx, scene_, kFormat, {}), "SceneResources::load");
        pipelines_ = &g_renderer->host_pipelines();
        must(pipelines_->ensure(HostPass::TileToAccum, kFormat), "HostPipelines::ensure");
        bare_texture_ = must(
            GpuImage::create(ctx, "bare.texture", kWidth, kHeight, kFormat,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, false),
            "bare texture");
        must(upload_image(ctx, bare_texture_, make_image(kWidth, kHeight, c.alpha)),
             "bare texture upload");
        accumulation_ = must(
            GpuImage::create(ctx, "limit.accumulation", kWidth, kHeight, kFormat,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                 VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                             true),
            "accumulation");
        check_tiled_matches_host();
        for (int i = 0; i < kWarmupRounds; ++i) {
            host_ms();
            tiled();
            bare();
        }
    }

    // The compositor's GPU time for its tile pass ("floor 0 tiles").
    double host_ms() {
        const FrameStats stats = must(compositor_->render(0), "Compositor::render");
        for (const PassTiming& p : stats.gpu_passes)
            if (p.name.starts_with("floor 0 tiles")) return p.milliseconds;
        die("the compositor timed no \"floor 0 tiles\" pass");
    }
    PassTimer::Times tiled() {
        return timer_.run([&](VkCommandBuffer cmd) { record_tiled(cmd); });
    }
    PassTimer::Times bare() {
        return timer_.run([&](VkCommandBuffer cmd) {
            begin_pass(cmd);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, g_bare_pipeline);
            push_texture(cmd, bare_texture_.view(), pipelines_->nearest_sampler());
            pipelines_->push(cmd, canvas_push());
            vkCmdDraw(cmd, 4, 1, 0, 0);
            vkCmdEndRendering(cmd);
        });
    }

    static VkPipeline g_bare_pipeline;

  private:
    // tile.vert's constants for a quad over the whole canvas.
    TilePushConstants canvas_push() const {
        TilePushConstants pc;
        pc.tile_rect[2] = float(kWidth);
        pc.tile_rect[3] = float(kHeight);
        pc.canvas_size[0] = float(kWidth);
        pc.canvas_size[1] = float(kHeight);
        return pc;
    }

    void begin_pass(VkCommandBuffer cmd) {
        accumulation_.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        color.imageView = accumulation_.view();
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {kWidth, kHeight}};
        info.layerCount = 1;
        info.colorAttachmentCount = 1;
        info.pColorAttachments = &color;
        vkCmdBeginRendering(cmd, &info);
        const VkViewport viewport{0, 0, float(kWidth), float(kHeight), 0, 1};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        const VkRect2D scissor{{0, 0}, {kWidth, kHeight}};
        vkCmdSetScissor(cmd, 0, 1, &scissor);
    }

    void push_texture(VkCommandBuffer cmd, VkImageView view, VkSampler sampler) {
        const VkDescriptorImageInfo image{sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.dstBinding = HostPipelines::kPrimaryImage;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        write.pImageInfo = &image;
        g_context->push_descriptor_fn()(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_->layout(),
                                        0, 1, &write);
    }

    // What Compositor::draw_tiles records for this tile in the normal view.
    void record_tiled(VkCommandBuffer cmd) {
        const LoadedTile& tile = resources_->floors().at(0).tiles.at(0);
        begin_pass(cmd);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                          pipelines_->pipeline(HostPass::TileToAccum, kFormat));
        push_texture(cmd, tile.texture->view(), pipelines_->tile_sampler(tile.one_to_one));
        TilePushConstants pc = canvas_push();
        pc.tile_rect[0] = float(tile.rect.x);
        pc.tile_rect[1] = float(tile.rect.y);
        pc.tile_rect[2] = float(tile.rect.width);
        pc.tile_rect[3] = float(tile.rect.height);
        pipelines_->push(cmd, pc);
        vkCmdDraw(cmd, 4, 1, 0, 0);
        vkCmdEndRendering(cmd);
    }

    // The hand recording must draw what the host draws, or the comparison means nothing: the
    // tile pass over a cleared accumulation, put over the background as output.frag does,
    // against the compositor's output.
    void check_tiled_matches_host() {
        must(compositor_->render(0), "Compositor::render");
        const ImageRGBA host = must(compositor_->read_output(), "reading the host's output");
        timer_.run([&](VkCommandBuffer cmd) {
            accumulation_.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
            const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(cmd, accumulation_.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                 &zero, 1, &range);
            record_tiled(cmd);
        });
        const ImageRGBA acc = must(read_back_image(*g_context, accumulation_), "read back");
        const auto& bg = scene_.background;
        double max_diff = 0;
        for (size_t i = 0; i < acc.pixels.size(); i += 4) {
            const float a = acc.pixels[i + 3];
            for (size_t c = 0; c < 4; ++c) {
                const float under = c < 3 ? bg[c] * bg[3] : bg[3];
                const float expected = acc.pixels[i + c] + under * (1.0f - a);
                max_diff = std::max(max_diff, double(std::fabs(expected - host.pixels[i + c])));
            }
        }
        if (max_diff > 1e-3)
            die(
                fmt::format("the hand-recorded tile pass draws a different image (max "
                            "difference {})",
                            max_diff));
    }

    SceneDesc scene_;
    std::unique_ptr<Compositor> compositor_;
    std::unique_ptr<SceneResources> resources_;
    HostPipelines* pipelines_ = nullptr;
    GpuImage bare_texture_, accumulation_;
    PassTimer timer_;
};

VkPipeline LimitCase::g_bare_pipeline = VK_NULL_HANDLE;

// ---------------------------------------------------------------------------------------------
// Benchmark and summary

struct Row {
    std::string name;
    size_t rounds = 0;
    double host_gpu = 0, tiled_gpu = 0, bare_gpu = 0, tiled_wall = 0, bare_wall = 0;
};
std::vector<Row> g_rows;

void bm_limit(benchmark::State& state, Case c) {
    LimitCase limit(c);
    std::vector<double> host_gpu, tiled_gpu, bare_gpu, tiled_wall, bare_wall;
    uint64_t round = 0;
    for (auto _ : state) {
        double tiled_ms = 0;
        for (uint64_t k = 0; k < 3; ++k) {
            switch ((round + k) % 3) {
                case 0:
                    host_gpu.push_back(limit.host_ms());
                    break;
                case 1: {
                    const PassTimer::Times t = limit.tiled();
                    tiled_gpu.push_back(t.gpu_ms);
                    tiled_wall.push_back(t.wall_ms);
                    tiled_ms = t.gpu_ms;
                    break;
                }
                case 2: {
                    const PassTimer::Times t = limit.bare();
                    bare_gpu.push_back(t.gpu_ms);
                    bare_wall.push_back(t.wall_ms);
                    break;
                }
            }
        }
        ++round;
        state.SetIterationTime(tiled_ms / 1000.0);
    }
    Row row{c.name,           host_gpu.size(),    median(host_gpu), median(tiled_gpu),
            median(bare_gpu), median(tiled_wall), median(bare_wall)};
    state.counters["bare_ms"] = row.bare_gpu;
    state.counters["tiled_ms"] = row.tiled_gpu;
    state.counters["host_ms"] = row.host_gpu;
    state.counters["tiled_over_bare"] = row.tiled_gpu / row.bare_gpu;
    state.counters["host_over_bare"] = row.host_gpu / row.bare_gpu;
    g_rows.push_back(row);
}

void print_summary() {
    std::printf(
        "\n## Summary: tile pass vs bare over pass, 1920x1080 RGBA16F (medians, interleaved)\n\n"
        "| case | rounds | bare GPU ms | tiled GPU ms | host GPU ms | tiled/bare | host/bare "
        "| bare wall ms | tiled wall ms | tiled/bare (wall) |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Row& r : g_rows)
        std::printf("| %s | %zu | %.2f | %.2f | %.2f | %.3f | %.3f | %.2f | %.2f | %.3f |\n",
                    r.name.c_str(), r.rounds, r.bare_gpu, r.tiled_gpu, r.host_gpu,
                    r.tiled_gpu / r.bare_gpu, r.host_gpu / r.bare_gpu, r.bare_wall, r.tiled_wall,
                    r.tiled_wall / r.bare_wall);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    ContextOptions options = ContextOptions::from_environment();
    const char* check = std::getenv("ACETATE_BENCHMARK_VALIDATION");
    options.validation = check && std::string(check) == "1";
    g_context = must(VulkanContext::create(options), "VulkanContext::create");
    g_renderer = must(Renderer::create(*g_context, RendererOptions{}), "Renderer::create");
    g_scratch = std::filesystem::temp_directory_path() /
                fmt::format("acetate-limit-benchmark-{}", ::getpid());
    std::filesystem::create_directories(g_scratch);
    benchmark::AddCustomContext("device", g_context->device_name());
    benchmark::AddCustomContext("nproc", std::to_string(sysconf(_SC_NPROCESSORS_ONLN)));
    LimitCase::g_bare_pipeline = create_bare_pipeline();

    const std::vector<Case> cases = {
        {"1to1/partial-alpha", Alpha::Partial, 1},
        {"1to1/quarter-alpha-0", Alpha::Gaps, 1},
        {"x2/partial-alpha", Alpha::Partial, 2},
    };
    for (const Case& c : cases)
        benchmark::RegisterBenchmark(("limit/" + c.name).c_str(), bm_limit, c)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->Iterations(40);

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
    vkDestroyPipeline(g_context->device(), LimitCase::g_bare_pipeline, nullptr);
    g_renderer.reset();
    g_context.reset();
    std::filesystem::remove_all(g_scratch);
    benchmark::Shutdown();
    return status;
}
