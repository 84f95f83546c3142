#pragma once
// The Vulkan commands every pass of the host records, in one place: dynamic rendering begun
// over an area into a colour target (and the floor's stencil), whole-image clears, the
// viewport and scissor. Each comes twice: inside a compiled frame (render/compiled_frame.hpp)
// the barriers are planned and recorded before the pass, so the `_planned` helpers record none
// and expect each image in its layout; outside one (the load's clears and warm-up, the camera's
// masks) the plain helpers record the layout transition first (a full barrier:
// GpuImage::transition), so a caller never pairs a barrier with a pass by hand.

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
// vkCmdEndRendering. Transitions the attachments to attachment layouts first; a stencil
// already in that layout still gets the barrier that makes earlier writes visible.
void begin_rendering(VkCommandBuffer cmd, const PixelRect& area, const ColourAttachment& colour,
                     const StencilAttachment* stencil = nullptr);
// The same with the attachments already in their layouts (COLOR_ATTACHMENT_OPTIMAL,
// DEPTH_STENCIL_ATTACHMENT_OPTIMAL) and the barriers recorded: no barrier of its own.
void begin_rendering_planned(VkCommandBuffer cmd, const PixelRect& area,
                             const ColourAttachment& colour,
                             const StencilAttachment* stencil = nullptr);

// Fills `area` of `image` (already a colour attachment) with `colour`: a pass that only clears
// (vkCmdClearColorImage cannot be limited to an area). An empty area records nothing. Planned.
void fill_area_planned(VkCommandBuffer cmd, GpuImage& image, const PixelRect& area,
                       const Rgba& colour);

// Clears the whole of a colour image (to transparent unless told) or a stencil image (to 0).
void clear_image(VkCommandBuffer cmd, GpuImage& image, const Rgba& colour = {0, 0, 0, 0});
// The same for a colour image already in TRANSFER_DST_OPTIMAL (a compiled frame's clear).
void clear_image_planned(VkCommandBuffer cmd, GpuImage& image, const Rgba& colour = {0, 0, 0, 0});
void clear_stencil_image(VkCommandBuffer cmd, GpuImage& image);

// A viewport of `width` x `height` pixels from the origin, and the scissor `rect`.
void set_viewport_and_scissor(VkCommandBuffer cmd, uint32_t width, uint32_t height,
                              const PixelRect& rect);

}  // namespace acetate
