#include "render/frame_targets.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "vulkan/vulkan_context.hpp"

namespace acetate {

const char* to_string(SharedRole role) {
    switch (role) {
        case SharedRole::FloorColour:
            return "floor colour";
        case SharedRole::FloorPingpong:
            return "floor ping-pong";
        case SharedRole::CompositePingpong:
            return "composite ping-pong";
    }
    return "?";
}

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
    if (needs.floor_target)
        ACETATE_TRY(
            make(floor_stencil_, "floor.stencil", context.stencil_format(),
                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT));
    const std::array<bool, kSharedRoles> roles{needs.floor_target, needs.floor_effects,
                                               needs.global_effects};
    size_t role_count = 0;
    for (size_t r = 0; r < kSharedRoles; ++r) {
        stand_ins_[r].reset();
        if (!roles[r]) continue;
        ++role_count;
        stand_ins_[r] = GpuImage::stand_in(to_string(SharedRole(r)), width, height, format);
    }
    // At most two roles are in use at once (see the header).
    const size_t images = needs.share_roles ? std::min<size_t>(role_count, 2) : role_count;
    shared_.clear();
    for (size_t i = 0; i < images; ++i) {
        std::optional<GpuImage> image;
        ACETATE_TRY(make_colour(image, fmt::format("transient.{}", i).c_str()));
        shared_.push_back(std::move(*image));
    }
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
    for (auto& image : self.shared_) out.push_back(&image);
    if (self.floor_stencil_) out.push_back(&*self.floor_stencil_);
    for (auto* image : self.effect_targets_.images()) out.push_back(image);
    return out;
}

RoleImages FrameTargets::stand_ins() {
    RoleImages out;
    for (size_t r = 0; r < kSharedRoles; ++r) out.image[r] = opt(stand_ins_[r]);
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
