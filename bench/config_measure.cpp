#include "config_measure.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include "render/compositor.hpp"
#include "render/renderer.hpp"

namespace acetate::bench {
namespace {

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

VkFormat parse_format(const std::string& name) {
    if (name == "rgba16f") return VK_FORMAT_R16G16B16A16_SFLOAT;
    if (name == "rgba32f") return VK_FORMAT_R32G32B32A32_SFLOAT;
    return VK_FORMAT_UNDEFINED;
}

Result<Measurement> measure_config(Renderer& renderer, const SceneDesc& scene, VkFormat format,
                                   uint32_t floor, uint32_t frames, double time) {
    CompositorOptions options;
    options.format = format;
    options.gpu_timings = true;
    auto compositor = Compositor::load(renderer, scene, options);
    if (!compositor) return compositor.error();
    Compositor& c = *compositor.value();

    Measurement out;
    ConfigResult& r = out.result;
    r.floor = floor;
    r.frames = frames;
    r.load_ms = c.load_stats().milliseconds;
    auto first = c.render(floor, time);
    if (!first) return first.error();
    r.first_frame_ms = first->milliseconds;

    std::vector<double> frame_ms;
    std::vector<std::string> pass_order;  // as the frame records them
    std::map<std::string, std::vector<double>> pass_ms;
    for (uint32_t i = 0; i < frames; ++i) {
        auto stats = c.render(floor, time);
        if (!stats) return stats.error();
        frame_ms.push_back(stats->milliseconds);
        r.pixels_shaded = stats->pixels_shaded;
        for (const PassTiming& p : stats->gpu_passes) {
            auto& samples = pass_ms[p.name];
            if (samples.empty()) pass_order.push_back(p.name);
            samples.push_back(p.milliseconds);
        }
    }
    r.median_ms = median(frame_ms);
    r.min_ms = frame_ms.empty() ? 0 : *std::min_element(frame_ms.begin(), frame_ms.end());
    r.max_ms = frame_ms.empty() ? 0 : *std::max_element(frame_ms.begin(), frame_ms.end());
    for (const std::string& name : pass_order) {
        r.gpu_passes.push_back({name, median(pass_ms[name])});
        r.gpu_total_ms += r.gpu_passes.back().milliseconds;
    }
    const auto fetch = std::chrono::steady_clock::now();
    auto image = c.read_output();
    if (!image) return image.error();
    out.readback_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - fetch).count();
    out.image = std::move(image.value());
    return out;
}

Result<FrameLimits> measure_limits(Renderer& renderer, const SceneDesc& scene, uint32_t floor,
                                   uint32_t frames, double time) {
    auto compositor = Compositor::load(renderer, scene, CompositorOptions{});
    if (!compositor) return compositor.error();
    Compositor& c = *compositor.value();
    FrameLimits out;
    out.scene = scene.file.string();
    out.floor = floor;
    // Frames at `at` after one already rendered: their median.
    auto steady = [&](uint32_t at, FrameStats* last) -> Result<double> {
        std::vector<double> ms;
        for (uint32_t i = 0; i < std::max(frames, 1u); ++i) {
            auto stats = c.render(at, time);
            if (!stats) return stats.error();
            ms.push_back(stats->milliseconds);
            if (last) *last = stats.value();
        }
        return median(ms);
    };
    auto first = c.render(floor, time);
    if (!first) return first.error();
    out.first_frame_ms = first->milliseconds;
    FrameStats last;
    auto at_floor = steady(floor, &last);
    if (!at_floor) return at_floor.error();
    out.steady_ms = at_floor.value();
    out.pixels_shaded = last.pixels_shaded;
    out.necessary_pixels = c.necessary_pixels(floor);
    if (c.floor_count() > 1) {
        out.switch_floor = floor == 0 ? int64_t(c.floor_count()) - 1 : 0;
        auto switched = c.render(uint32_t(out.switch_floor), time);
        if (!switched) return switched.error();
        out.switch_ms = switched->milliseconds;
        auto there = steady(uint32_t(out.switch_floor), nullptr);
        if (!there) return there.error();
        out.switch_steady_ms = there.value();
    }
    return out;
}

}  // namespace acetate::bench
