#include "render/frame_targets.hpp"

#include <algorithm>

#include "vulkan/vulkan_context.hpp"

namespace acetate {

Result<void> FrameTargets::allocate(VulkanContext& context, uint32_t width, uint32_t height,
                                    VkFormat format, const FrameTargetNeeds& needs,
                                    const std::string& where) {
    constexpr VkImageUsageFlags kColourUsage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
        VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto make = [&](std::optional<GpuImage>& slot, const char* name, VkFormat image_format,
                    VkImageUsageFlags usage) -> Result<void> {
        auto image = GpuImage::create(context, name, width, height, image_format, usage, true);
        if (!image)
            return make_error(image.error().code, where + ": " + image.error().message,
                              image.error().vk_result);
        slot = std::move(image.value());
        return {};
    };
    auto make_colour = [&](std::optional<GpuImage>& slot, const char* name) {
        return make(slot, name, format, kColourUsage);
    };
    std::optional<GpuImage> accumulation, output;
    ACETATE_TRY(make_colour(accumulation, "accumulation"));
    ACETATE_TRY(make_colour(output, "output"));
    accumulation_ = std::move(*accumulation);
    output_ = std::move(*output);
    if (needs.floor_target) {
        ACETATE_TRY(make_colour(floor_colour_, "floor.color"));
        ACETATE_TRY(
            make(floor_stencil_, "floor.stencil", context.stencil_format(),
                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT));
    }
    if (needs.floor_effects) ACETATE_TRY(make_colour(floor_pingpong_, "floor.pingpong"));
    if (needs.global_effects)
        ACETATE_TRY(make_colour(accumulation_pingpong_, "accumulation.pingpong"));
    auto violations = GpuBuffer::create(
        context, VkDeviceSize(sizeof(uint32_t) * std::max<size_t>(1, needs.floor_count)),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!violations) return violations.error();
    violations_ = std::move(violations.value());
    return {};
}

template <typename Self>
auto FrameTargets::list_images(Self& self) {
    std::vector<decltype(&self.accumulation_)> out{&self.accumulation_, &self.output_};
    for (auto* optional : {&self.accumulation_pingpong_, &self.floor_colour_, &self.floor_stencil_,
                           &self.floor_pingpong_})
        if (optional->has_value()) out.push_back(&optional->value());
    for (auto* image : self.effect_targets_.images()) out.push_back(image);
    return out;
}

std::vector<GpuImage*> FrameTargets::images() {
    return list_images(*this);
}

std::vector<const GpuImage*> FrameTargets::images() const {
    return list_images(*this);
}

std::vector<TargetInfo> FrameTargets::infos() const {
    std::vector<TargetInfo> out;
    for (const GpuImage* image : images())
        out.push_back({image->name(), format_name(image->format()), image->width(), image->height(),
                       image->bytes()});
    return out;
}

}  // namespace acetate
