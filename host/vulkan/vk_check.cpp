#include "vulkan/vk_check.hpp"

#include <fmt/format.h>

namespace acetate {

Error vk_error(const char* call, VkResult result) {
    const ErrorCode code =
        (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
            ? ErrorCode::OutOfMemory
            : ErrorCode::VulkanCall;
    return make_error(code, fmt::format("{} failed with VkResult {}", call, int(result)),
                      int32_t(result));
}

}  // namespace acetate
