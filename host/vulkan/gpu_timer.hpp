#pragma once
// GPU time between points of a recorded frame, from Vulkan timestamp queries: what
// acetate-bench shows as "where the time goes". Measurement only: a compositor makes one when
// asked (CompositorOptions::gpu_timings), and a frame without it records no query.

#include <vulkan/vulkan.h>

#include <memory>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "vulkan/pass_timing.hpp"

namespace acetate {

class VulkanContext;

class GpuTimer {
  public:
    // Fails (DeviceLimit) when the queue writes no timestamps (timestampValidBits == 0).
    // `capacity`: the most marks one frame records; later marks in a frame are not timed.
    static Result<std::unique_ptr<GpuTimer>> create(VulkanContext& context, uint32_t capacity);
    ~GpuTimer();
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;

    // Starts a frame: resets the queries and writes the first timestamp. Outside any rendering.
    void begin(VkCommandBuffer cmd);
    // The GPU time since the previous mark (or begin) is `name`'s: written once every command
    // recorded before it has completed (bottom of pipe), so the intervals add up to the frame.
    void mark(VkCommandBuffer cmd, const std::string& name);
    // After the frame's submission has completed: each interval, in recording order.
    Result<std::vector<PassTiming>> read() const;

  private:
    GpuTimer(VulkanContext& context) : context_(context) {}
    VulkanContext& context_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    uint32_t capacity_ = 0;
    uint64_t valid_mask_ = 0;
    double nanoseconds_per_tick_ = 1;
    std::vector<std::string> names_;  // names_[i] ends at query i + 1
};

}  // namespace acetate
