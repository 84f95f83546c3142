#pragma once
// What the compositor's two source files share (compositor.cpp records frames,
// compositor_load.cpp loads scenes): Vulkan structs filled the way both use them.

#include <vulkan/vulkan.h>

#include <chrono>

#include "core/pixel_rect.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::compositor_detail {

inline constexpr VkImageUsageFlags kTargetUsage =
    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
    VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;

inline VkRect2D to_vk(const PixelRect& r) {
    return {{int32_t(r.x0), int32_t(r.y0)}, {uint32_t(r.x1 - r.x0), uint32_t(r.y1 - r.y0)}};
}

inline VkRenderingAttachmentInfo color_attachment(VkImageView view, bool clear) {
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = view;
    a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    a.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    return a;
}

inline double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// What a load or a frame allocated, loaded or compiled: the counters' growth.
inline ResourceCounters delta(const ResourceCounters& after, const ResourceCounters& before) {
    return {after.images_loaded - before.images_loaded,
            after.targets_allocated - before.targets_allocated,
            after.shaders_compiled - before.shaders_compiled,
            after.pipelines_created - before.pipelines_created};
}

}  // namespace acetate::compositor_detail
