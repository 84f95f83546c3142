#include "vulkan/gpu_image.hpp"

#include <Imath/half.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "vulkan/vk_check.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {

uint32_t bytes_per_pixel(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8G8B8A8_UNORM:
            return 4;
        case VK_FORMAT_R16_SFLOAT:
            return 2;
        case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_R32_SFLOAT:
            return 4;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT:
            return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return 16;
        case VK_FORMAT_S8_UINT:
            return 1;
        case VK_FORMAT_D24_UNORM_S8_UINT:
            return 4;
        case VK_FORMAT_D32_SFLOAT_S8_UINT:
            return 8;
        default:
            return 0;
    }
}

const char* format_name(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8G8B8A8_UNORM:
            return "rgba8";
        case VK_FORMAT_R16G16B16A16_SFLOAT:
            return "rgba16f";
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return "rgba32f";
        case VK_FORMAT_S8_UINT:
            return "s8";
        case VK_FORMAT_D24_UNORM_S8_UINT:
            return "d24s8";
        case VK_FORMAT_D32_SFLOAT_S8_UINT:
            return "d32s8";
        default:
            return "other";
    }
}

static bool is_stencil_format(VkFormat f) {
    return f == VK_FORMAT_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT ||
           f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

Result<GpuImage> GpuImage::create(VulkanContext& context, std::string name, uint32_t width,
                                  uint32_t height, VkFormat format, VkImageUsageFlags usage,
                                  bool is_target) {
    const uint32_t max_dim = context.properties().limits.maxImageDimension2D;
    if (width == 0 || height == 0 || width > max_dim || height > max_dim)
        return make_error(ErrorCode::DeviceLimit,
                          fmt::format("image \"{}\" is {}x{}; device \"{}\" allows 1..{} per side",
                                      name, width, height, context.device_name(), max_dim));
    GpuImage out;
    out.context_ = &context;
    out.name_ = std::move(name);
    out.width_ = width;
    out.height_ = height;
    out.format_ = format;
    out.aspect_ = format == VK_FORMAT_S8_UINT ? VkImageAspectFlags(VK_IMAGE_ASPECT_STENCIL_BIT)
                  : is_stencil_format(format)
                      ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT)
                      : VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT);
    VkDevice device = context.device();

    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkResult r = vkCreateImage(device, &info, nullptr, &out.image_);
    if (r != VK_SUCCESS)
        return make_error(r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY
                              ? ErrorCode::OutOfMemory
                              : ErrorCode::DeviceLimit,
                          fmt::format("cannot create image \"{}\" {}x{} {} (VkResult {})",
                                      out.name_, width, height, format_name(format), int(r)),
                          r);

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, out.image_, &req);
    auto type = context.find_memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!type) return type.error();
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type.value();
    r = vkAllocateMemory(device, &alloc, nullptr, &out.memory_);
    if (r != VK_SUCCESS)
        return make_error(ErrorCode::OutOfMemory,
                          fmt::format("cannot allocate {} bytes for image \"{}\" (VkResult {})",
                                      req.size, out.name_, int(r)),
                          r);
    out.bytes_ = req.size;
    ACETATE_VK(vkBindImageMemory(device, out.image_, out.memory_, 0));

    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = out.image_;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {out.aspect_, 0, 1, 0, 1};
    ACETATE_VK(vkCreateImageView(device, &view, nullptr, &out.view_));
    if (is_target) ++context.counters().targets_allocated;
    return out;
}

GpuImage GpuImage::stand_in(std::string name, uint32_t width, uint32_t height, VkFormat format) {
    GpuImage out;
    out.name_ = std::move(name);
    out.width_ = width;
    out.height_ = height;
    out.format_ = format;
    return out;
}

GpuImage::~GpuImage() {
    release();
}

GpuImage::GpuImage(GpuImage&& other) noexcept {
    *this = std::move(other);
}

GpuImage& GpuImage::operator=(GpuImage&& other) noexcept {
    if (this != &other) {
        release();
        context_ = other.context_;
        image_ = other.image_;
        memory_ = other.memory_;
        view_ = other.view_;
        format_ = other.format_;
        aspect_ = other.aspect_;
        layout_ = other.layout_;
        width_ = other.width_;
        height_ = other.height_;
        bytes_ = other.bytes_;
        name_ = std::move(other.name_);
        other.context_ = nullptr;
        other.image_ = VK_NULL_HANDLE;
        other.memory_ = VK_NULL_HANDLE;
        other.view_ = VK_NULL_HANDLE;
    }
    return *this;
}

void GpuImage::release() {
    if (!context_) return;
    VkDevice device = context_->device();
    if (view_) vkDestroyImageView(device, view_, nullptr);
    if (image_) vkDestroyImage(device, image_, nullptr);
    if (memory_) vkFreeMemory(device, memory_, nullptr);
    context_ = nullptr;
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
}

void GpuImage::transition(VkCommandBuffer cmd, VkImageLayout layout) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    barrier.oldLayout = layout_;
    barrier.newLayout = layout;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image_;
    barrier.subresourceRange = {aspect_, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
    if (context_) ++context_->counters().barriers_recorded;
    layout_ = layout;
}

void GpuImage::record_barrier(VkCommandBuffer cmd, const ImageTransition* transitions,
                              size_t count) {
    constexpr size_t kMostAtOnce = 8;  // a pass touches at most an input set and two attachments
    VkImageMemoryBarrier2 barriers[kMostAtOnce];
    for (size_t first = 0; first < count; first += kMostAtOnce) {
        const size_t n = std::min(kMostAtOnce, count - first);
        for (size_t i = 0; i < n; ++i) {
            const ImageTransition& t = transitions[first + i];
            VkImageMemoryBarrier2& b = barriers[i];
            b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
            b.srcStageMask = t.src_stages;
            b.srcAccessMask = t.src_access;
            b.dstStageMask = t.dst_stages;
            b.dstAccessMask = t.dst_access;
            b.oldLayout = t.image->layout_;
            b.newLayout = t.layout;
            b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.image = t.image->image_;
            b.subresourceRange = {t.image->aspect_, 0, 1, 0, 1};
            t.image->layout_ = t.layout;
        }
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = uint32_t(n);
        dep.pImageMemoryBarriers = barriers;
        vkCmdPipelineBarrier2(cmd, &dep);
        if (VulkanContext* context = transitions[first].image->context_)
            ++context->counters().barriers_recorded;
    }
}

Result<GpuBuffer> GpuBuffer::create(VulkanContext& context, VkDeviceSize size,
                                    VkBufferUsageFlags usage) {
    GpuBuffer out;
    out.context_ = &context;
    out.size_ = size;
    VkDevice device = context.device();
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    ACETATE_VK(vkCreateBuffer(device, &info, nullptr, &out.buffer_));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, out.buffer_, &req);
    auto type =
        context.find_memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                         VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (!type) return type.error();
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type.value();
    VkResult r = vkAllocateMemory(device, &alloc, nullptr, &out.memory_);
    if (r != VK_SUCCESS)
        return make_error(
            ErrorCode::OutOfMemory,
            fmt::format("cannot allocate a {}-byte buffer (VkResult {})", size, int(r)), r);
    ACETATE_VK(vkBindBufferMemory(device, out.buffer_, out.memory_, 0));
    ACETATE_VK(vkMapMemory(device, out.memory_, 0, VK_WHOLE_SIZE, 0, &out.mapped_));
    return out;
}

GpuBuffer::~GpuBuffer() {
    release();
}

GpuBuffer::GpuBuffer(GpuBuffer&& other) noexcept {
    *this = std::move(other);
}

GpuBuffer& GpuBuffer::operator=(GpuBuffer&& other) noexcept {
    if (this != &other) {
        release();
        context_ = other.context_;
        buffer_ = other.buffer_;
        memory_ = other.memory_;
        mapped_ = other.mapped_;
        size_ = other.size_;
        other.context_ = nullptr;
        other.buffer_ = VK_NULL_HANDLE;
        other.memory_ = VK_NULL_HANDLE;
        other.mapped_ = nullptr;
    }
    return *this;
}

void GpuBuffer::release() {
    if (!context_) return;
    VkDevice device = context_->device();
    if (mapped_) vkUnmapMemory(device, memory_);
    if (buffer_) vkDestroyBuffer(device, buffer_, nullptr);
    if (memory_) vkFreeMemory(device, memory_, nullptr);
    context_ = nullptr;
}

namespace {

void copy_region(VkCommandBuffer cmd, GpuImage& image, VkBuffer buffer, bool to_image) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {image.width(), image.height(), 1};
    if (to_image)
        vkCmdCopyBufferToImage(cmd, buffer, image.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &region);
    else
        vkCmdCopyImageToBuffer(cmd, image.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1,
                               &region);
}

}  // namespace

Result<void> upload_image(VulkanContext& context, GpuImage& image, const ImageRGBA& pixels) {
    if (pixels.width != image.width() || pixels.height != image.height())
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("upload to \"{}\": size mismatch", image.name()));
    return upload_texels(context, image, pixels.pixels.data(), 4);
}

Result<void> upload_texels(VulkanContext& context, GpuImage& image, const float* texels,
                           uint32_t channels) {
    const size_t count = size_t(image.width()) * image.height() * channels;
    const uint32_t bpp = bytes_per_pixel(image.format());
    const bool half = image.format() == VK_FORMAT_R16_SFLOAT ||
                      image.format() == VK_FORMAT_R16G16_SFLOAT ||
                      image.format() == VK_FORMAT_R16G16B16A16_SFLOAT;
    const bool unorm = image.format() == VK_FORMAT_R8G8B8A8_UNORM;
    // Each format holds bpp bytes per texel: 2 per half, 4 per float, 1 per unorm channel.
    if (bpp == 0 || bpp != channels * (half ? 2u : unorm ? 1u : 4u))
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("upload to \"{}\": {} channels do not fit format {}",
                                      image.name(), channels, format_name(image.format())));
    auto staging = GpuBuffer::create(context, VkDeviceSize(image.width()) * image.height() * bpp,
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    if (!staging) return staging.error();
    const float* src = texels;
    if (half) {
        auto* dst = static_cast<uint16_t*>(staging->mapped());
        // Finite values beyond the half range would become Inf; the contract allows none, so
        // they saturate at +-65504 (the largest half).
        for (size_t i = 0; i < count; ++i)
            dst[i] = Imath::half(std::clamp(src[i], -65504.0f, 65504.0f)).bits();
    } else if (unorm) {
        auto* dst = static_cast<uint8_t*>(staging->mapped());
        for (size_t i = 0; i < count; ++i) {
            const float v = src[i] < 0 ? 0 : src[i] > 1 ? 1 : src[i];
            dst[i] = uint8_t(v * 255.0f + 0.5f);
        }
    } else {
        std::memcpy(staging->mapped(), src, count * sizeof(float));
    }
    return context.submit_and_wait([&](VkCommandBuffer cmd) {
        image.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        copy_region(cmd, image, staging->buffer(), true);
        image.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
}

Result<ImageRGBA> read_back_image(VulkanContext& context, GpuImage& image) {
    const uint32_t bpp = bytes_per_pixel(image.format());
    const size_t pixel_count = size_t(image.width()) * image.height();
    auto staging = GpuBuffer::create(context, VkDeviceSize(pixel_count) * bpp,
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    if (!staging) return staging.error();
    const VkImageLayout previous = image.layout();
    ACETATE_TRY(context.submit_and_wait([&](VkCommandBuffer cmd) {
        image.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        copy_region(cmd, image, staging->buffer(), false);
        if (previous != VK_IMAGE_LAYOUT_UNDEFINED) image.transition(cmd, previous);
    }));
    ImageRGBA out(image.width(), image.height());
    const size_t count = pixel_count * 4;
    switch (image.format()) {
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            std::memcpy(out.pixels.data(), staging->mapped(), count * sizeof(float));
            break;
        case VK_FORMAT_R16G16B16A16_SFLOAT: {
            const auto* src = static_cast<const uint16_t*>(staging->mapped());
            for (size_t i = 0; i < count; ++i) {
                Imath::half h;
                h.setBits(src[i]);
                out.pixels[i] = float(h);
            }
            break;
        }
        case VK_FORMAT_R8G8B8A8_UNORM: {
            const auto* src = static_cast<const uint8_t*>(staging->mapped());
            for (size_t i = 0; i < count; ++i) out.pixels[i] = src[i] / 255.0f;
            break;
        }
        default:
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("read back \"{}\": unsupported format", image.name()));
    }
    return out;
}

}  // namespace acetate
