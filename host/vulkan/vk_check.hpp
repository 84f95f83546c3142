#pragma once
// ACETATE_VK: checks a Vulkan call's VkResult and returns an Error naming the call. Kept out of
// core/result.hpp so that core, and the registry built on it, include no Vulkan header.

#include <vulkan/vulkan.h>

#include "core/result.hpp"

namespace acetate {
// The Error for a failed Vulkan call: OutOfMemory for the two out-of-memory results, else
// VulkanCall; the message names the call and the VkResult.
Error vk_error(const char* call, VkResult result);
}  // namespace acetate

#define ACETATE_VK(call)                                           \
    do {                                                           \
        VkResult acetate_vk_result_ = (call);                      \
        if (acetate_vk_result_ != VK_SUCCESS)                      \
            return ::acetate::vk_error(#call, acetate_vk_result_); \
    } while (0)
