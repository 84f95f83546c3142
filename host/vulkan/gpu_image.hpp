#pragma once
// GPU images and buffers with their memory, owned RAII-style, plus the transfers the host
// needs: upload a CPU image, read one back as float.

#include <vulkan/vulkan.h>

#include <string>

#include "core/image_rgba.hpp"
#include "core/result.hpp"

namespace acetate {

class VulkanContext;
class GpuImage;

// One image's part of a planned pipeline barrier (render/frame_barriers.cpp): from the stages
// and accesses that touched it since its last barrier to those that will, into `layout`.
struct ImageTransition {
    GpuImage* image = nullptr;
    VkPipelineStageFlags2 src_stages = 0, dst_stages = 0;
    VkAccessFlags2 src_access = 0, dst_access = 0;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

// A 2D image with its own memory and one view.
class GpuImage {
  public:
    GpuImage() = default;
    // Creates a device-local image; counts one allocated render target when `is_target`.
    // Fails with DeviceLimit when the size exceeds maxImageDimension2D.
    static Result<GpuImage> create(VulkanContext& context, std::string name, uint32_t width,
                                   uint32_t height, VkFormat format, VkImageUsageFlags usage,
                                   bool is_target);
    // An image with a name, a size and a format and no Vulkan objects: what a frame is first
    // compiled over to learn when each of its interchangeable images is used, before the images
    // they will share are chosen (render/frame_targets.hpp). Recording with one is a bug.
    static GpuImage stand_in(std::string name, uint32_t width, uint32_t height, VkFormat format);
    ~GpuImage();
    GpuImage(GpuImage&& other) noexcept;
    GpuImage& operator=(GpuImage&& other) noexcept;
    GpuImage(const GpuImage&) = delete;
    GpuImage& operator=(const GpuImage&) = delete;

    VkImage image() const { return image_; }
    VkImageView view() const { return view_; }
    VkFormat format() const { return format_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    const std::string& name() const { return name_; }
    VkImageAspectFlags aspect() const { return aspect_; }
    uint64_t bytes() const { return bytes_; }

    // The layout the image is left in by the last recorded transition.
    VkImageLayout layout() const { return layout_; }
    // Records a barrier to `layout` (full pipeline dependency; the host's passes are few and
    // each depends on the previous one, so finer stages would buy nothing on lavapipe).
    void transition(VkCommandBuffer cmd, VkImageLayout layout);
    // Records one pipeline barrier holding every transition (at least one), and leaves each
    // image in its new layout: a compiled frame's barriers before a pass, planned at compile
    // time, cost one command however many images the pass touches.
    static void record_barrier(VkCommandBuffer cmd, const ImageTransition* transitions,
                               size_t count);

  private:
    void release();
    VulkanContext* context_ = nullptr;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkImageAspectFlags aspect_ = VK_IMAGE_ASPECT_COLOR_BIT;
    VkImageLayout layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
    uint32_t width_ = 0, height_ = 0;
    uint64_t bytes_ = 0;
    std::string name_;
};

// A host-visible, coherent buffer, persistently mapped.
class GpuBuffer {
  public:
    GpuBuffer() = default;
    static Result<GpuBuffer> create(VulkanContext& context, VkDeviceSize size,
                                    VkBufferUsageFlags usage);
    ~GpuBuffer();
    GpuBuffer(GpuBuffer&& other) noexcept;
    GpuBuffer& operator=(GpuBuffer&& other) noexcept;
    GpuBuffer(const GpuBuffer&) = delete;
    GpuBuffer& operator=(const GpuBuffer&) = delete;

    VkBuffer buffer() const { return buffer_; }
    void* mapped() const { return mapped_; }
    VkDeviceSize size() const { return size_; }

  private:
    void release();
    VulkanContext* context_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    void* mapped_ = nullptr;
    VkDeviceSize size_ = 0;
};

// Bytes per pixel of the colour formats the host uses (RGBA8, and R, RG, RGBA in 16F and 32F).
uint32_t bytes_per_pixel(VkFormat format);
const char* format_name(VkFormat format);

// Copies `pixels` (RGBA float, same size as the image) into `image`, converting to its format
// (RGBA16F rounds to nearest half), and leaves it in SHADER_READ_ONLY_OPTIMAL.
Result<void> upload_image(VulkanContext& context, GpuImage& image, const ImageRGBA& pixels);
// The same for any of the float formats with 1, 2 or 4 channels: width * height texels of
// `channels` floats (the image's channel count, else InvalidInput).
Result<void> upload_texels(VulkanContext& context, GpuImage& image, const float* texels,
                           uint32_t channels);

// Reads a colour image back as RGBA float; leaves the image in its previous layout.
Result<ImageRGBA> read_back_image(VulkanContext& context, GpuImage& image);

}  // namespace acetate
