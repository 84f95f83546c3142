#pragma once
// The Vulkan commands every pass of the host records, in one place: dynamic rendering begun
// over an area into a colour target (and the floor's stencil), whole-image clears, the
// viewport and scissor. Every pass runs in a compiled frame (render/compiled_frame.hpp: the
// frames, the load's warm-up, the camera's masks), whose barriers are planned and recorded
// before the pass, so these record none and expect each image in the layout of its use.

#include <vulkan/vulkan.h>

#include <array>

#include "core/pixel_rect.hpp"
#include "vulkan/gpu_image.hpp"

namespace acetate {

using Rgba = std::array<float, 4>;

VkRect2D to_vk(const PixelRect& rect);

// What a rendering pass does with an attachment's old contents inside its area.
enum class LoadOp {
    Keep,      // load them (draws blend over them)
    Clear,     // clear to the given value first
    DontCare,  // every pixel of the area is written: no load
};

struct ColourAttachment {
    GpuImage* image = nullptr;
    LoadOp load = LoadOp::Keep;
    Rgba clear{0, 0, 0, 0};
};

// The floor's stencil (coverage). Its depth aspect, where the format has one, is attached too,
// as Vulkan asks of a combined depth-stencil image.
struct StencilAttachment {
    GpuImage* image = nullptr;
    LoadOp load = LoadOp::Keep;
    uint32_t clear = 0;
    bool store = true;  // false: later passes do not read what this one writes
};

// Begins rendering over `area` (the area loads and clears are limited to); end it with
// vkCmdEndRendering. The attachments are in their layouts (COLOR_ATTACHMENT_OPTIMAL,
// DEPTH_STENCIL_ATTACHMENT_OPTIMAL).
void begin_rendering(VkCommandBuffer cmd, const PixelRect& area, const ColourAttachment& colour,
                     const StencilAttachment* stencil = nullptr);

// Fills `area` of `image` (already a colour attachment) with `colour`: a pass that only clears
// (vkCmdClearColorImage cannot be limited to an area). An empty area records nothing.
void fill_area(VkCommandBuffer cmd, GpuImage& image, const PixelRect& area, const Rgba& colour);

// Clears the whole of a colour image (to transparent unless told) or a stencil image (to 0),
// in TRANSFER_DST_OPTIMAL.
void clear_image(VkCommandBuffer cmd, GpuImage& image, const Rgba& colour = {0, 0, 0, 0});
void clear_stencil(VkCommandBuffer cmd, GpuImage& image);

// A viewport of `width` x `height` pixels from the origin, and the scissor `rect`.
void set_viewport_and_scissor(VkCommandBuffer cmd, uint32_t width, uint32_t height,
                              const PixelRect& rect);

}  // namespace acetate
