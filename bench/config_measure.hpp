#pragma once
// Measures one configuration: loads the scene, renders the first frame after load, then the
// timed frames with GPU timestamps, and reads the last frame back.

#include <vulkan/vulkan.h>

#include "bench_results.hpp"
#include "core/result.hpp"
#include "scene/image_io.hpp"
#include "scene/scene.hpp"

namespace acetate {
class Renderer;
}

namespace acetate::bench {

struct Measurement {
    ConfigResult result;     // times, GPU passes and pixels shaded; no error yet
    ImageRGBA image;         // the output of the last timed frame
    double readback_ms = 0;  // fetching it to the CPU
};

// `result` fields scene, plugin, preset, format and reference are the caller's.
Result<Measurement> measure_config(Renderer& renderer, const SceneDesc& scene, VkFormat format,
                                   uint32_t floor, uint32_t frames, double time);

// The scene as given, in rgba16f: first frame after load, steady frames, the first frame after
// switching to another floor and steady frames there, pixels shaded against the minimum.
Result<FrameLimits> measure_limits(Renderer& renderer, const SceneDesc& scene, uint32_t floor,
                                   uint32_t frames, double time);

VkFormat parse_format(const std::string& name);  // VK_FORMAT_UNDEFINED when unknown

}  // namespace acetate::bench
