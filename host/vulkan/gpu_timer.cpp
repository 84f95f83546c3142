#include "vulkan/gpu_timer.hpp"

#include <fmt/format.h>

#include "vulkan/vulkan_context.hpp"

namespace acetate {

Result<std::unique_ptr<GpuTimer>> GpuTimer::create(VulkanContext& context, uint32_t capacity) {
    uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(context.physical_device(), &families, nullptr);
    std::vector<VkQueueFamilyProperties> properties(families);
    vkGetPhysicalDeviceQueueFamilyProperties(context.physical_device(), &families,
                                             properties.data());
    const uint32_t bits = properties.at(context.queue_family()).timestampValidBits;
    if (bits == 0)
        return make_error(ErrorCode::DeviceLimit,
                          fmt::format("{}: its queue writes no timestamps, so no GPU times",
                                      context.device_name()));
    std::unique_ptr<GpuTimer> timer(new GpuTimer(context));
    timer->capacity_ = capacity + 1;  // the start, then one query per mark
    timer->valid_mask_ = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
    timer->nanoseconds_per_tick_ = double(context.properties().limits.timestampPeriod);
    timer->names_.reserve(capacity);
    VkQueryPoolCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = timer->capacity_;
    if (VkResult r = vkCreateQueryPool(context.device(), &info, nullptr, &timer->pool_);
        r != VK_SUCCESS)
        return make_error(ErrorCode::VulkanCall,
                          fmt::format("vkCreateQueryPool failed ({})", int(r)));
    return timer;
}

GpuTimer::~GpuTimer() {
    if (pool_) vkDestroyQueryPool(context_.device(), pool_, nullptr);
}

void GpuTimer::begin(VkCommandBuffer cmd) {
    names_.clear();
    vkCmdResetQueryPool(cmd, pool_, 0, capacity_);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 0);
}

void GpuTimer::mark(VkCommandBuffer cmd, const std::string& name) {
    if (names_.size() + 1 >= capacity_) return;
    names_.push_back(name);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, uint32_t(names_.size()));
}

Result<std::vector<PassTiming>> GpuTimer::read() const {
    std::vector<PassTiming> out;
    if (names_.empty()) return out;
    std::vector<uint64_t> ticks(names_.size() + 1);
    if (VkResult r = vkGetQueryPoolResults(
            context_.device(), pool_, 0, uint32_t(ticks.size()), ticks.size() * sizeof(uint64_t),
            ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
        r != VK_SUCCESS)
        return make_error(ErrorCode::VulkanCall,
                          fmt::format("vkGetQueryPoolResults failed ({})", int(r)));
    for (size_t i = 0; i < names_.size(); ++i) {
        // Counters may wrap within their valid bits; the difference modulo 2^bits is right.
        const uint64_t elapsed = (ticks[i + 1] - ticks[i]) & valid_mask_;
        out.push_back({names_[i], double(elapsed) * nanoseconds_per_tick_ * 1e-6});
    }
    return out;
}

}  // namespace acetate
