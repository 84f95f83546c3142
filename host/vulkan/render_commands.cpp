#include "vulkan/render_commands.hpp"

#include <cstring>

namespace acetate {
namespace {

VkAttachmentLoadOp to_vk(LoadOp load) {
    switch (load) {
        case LoadOp::Clear:
            return VK_ATTACHMENT_LOAD_OP_CLEAR;
        case LoadOp::DontCare:
            return VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        case LoadOp::Keep:
            break;
    }
    return VK_ATTACHMENT_LOAD_OP_LOAD;
}

}  // namespace

VkRect2D to_vk(const PixelRect& r) {
    return {{int32_t(r.x0), int32_t(r.y0)}, {uint32_t(r.x1 - r.x0), uint32_t(r.y1 - r.y0)}};
}

void begin_rendering(VkCommandBuffer cmd, const PixelRect& area, const ColourAttachment& colour,
                     const StencilAttachment* stencil) {
    VkRenderingAttachmentInfo colour_info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colour_info.imageView = colour.image->view();
    colour_info.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colour_info.loadOp = to_vk(colour.load);
    colour_info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    std::memcpy(colour_info.clearValue.color.float32, colour.clear.data(), sizeof(float) * 4);

    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = to_vk(area);
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &colour_info;
    VkRenderingAttachmentInfo stencil_info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    if (stencil) {
        stencil_info.imageView = stencil->image->view();
        stencil_info.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        stencil_info.loadOp = to_vk(stencil->load);
        stencil_info.storeOp =
            stencil->store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_NONE;
        stencil_info.clearValue.depthStencil = {1.0f, stencil->clear};
        info.pStencilAttachment = &stencil_info;
        const bool has_depth = stencil->image->format() != VK_FORMAT_S8_UINT;
        info.pDepthAttachment = has_depth ? &stencil_info : nullptr;
    }
    vkCmdBeginRendering(cmd, &info);
}

void fill_area(VkCommandBuffer cmd, GpuImage& image, const PixelRect& area, const Rgba& colour) {
    if (area.empty()) return;
    begin_rendering(cmd, area, {&image, LoadOp::Clear, colour});
    vkCmdEndRendering(cmd);
}

void clear_image(VkCommandBuffer cmd, GpuImage& image, const Rgba& colour) {
    VkClearColorValue value;
    std::memcpy(value.float32, colour.data(), sizeof(value.float32));
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, image.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1,
                         &range);
}

void clear_stencil(VkCommandBuffer cmd, GpuImage& image) {
    const VkClearDepthStencilValue value{1.0f, 0};
    const VkImageSubresourceRange range{image.aspect(), 0, 1, 0, 1};
    vkCmdClearDepthStencilImage(cmd, image.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1,
                                &range);
}

void set_viewport_and_scissor(VkCommandBuffer cmd, uint32_t width, uint32_t height,
                              const PixelRect& rect) {
    const VkViewport viewport{0, 0, float(width), float(height), 0, 1};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    const VkRect2D scissor = to_vk(rect);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace acetate
