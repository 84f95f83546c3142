#pragma once
// Headless Vulkan start-up and the one queue the host renders on. No window system.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace acetate {

struct ContextOptions {
    // Turns on VK_LAYER_KHRONOS_validation and a messenger that records every message.
    // Default: the environment variable ACETATE_VALIDATION=1.
    bool validation = false;
    // Picks the device by index ("1") or case-insensitive name substring ("llvmpipe").
    // Default: ACETATE_DEVICE; empty = the first device of the best type: discrete GPU, then
    // integrated, virtual, CPU (lavapipe).
    std::string device_selector;

    static ContextOptions from_environment();
};

// Counters of expensive work, read before and after a frame to prove what a frame did.
struct ResourceCounters {
    uint64_t images_loaded = 0;
    uint64_t targets_allocated = 0;
    uint64_t shaders_compiled = 0;
    uint64_t pipelines_created = 0;
    // Pipeline barriers recorded: every image layout transition, and the one that makes a
    // submission's writes visible to the host. Not expensive alone; a frame's count shows how
    // much of it is synchronisation (a compiled frame plans fewer).
    uint64_t barriers_recorded = 0;
};
// What a load or a frame allocated, loaded or compiled: the counters' growth since `before`.
inline ResourceCounters operator-(const ResourceCounters& after, const ResourceCounters& before) {
    return {after.images_loaded - before.images_loaded,
            after.targets_allocated - before.targets_allocated,
            after.shaders_compiled - before.shaders_compiled,
            after.pipelines_created - before.pipelines_created,
            after.barriers_recorded - before.barriers_recorded};
}

class VulkanContext {
  public:
    // Creates instance, device and queue. Fails with NoDevice when nothing matches the selector,
    // VulkanInit when a required feature (Vulkan 1.3 dynamic rendering, synchronization2,
    // push descriptors, fragment stores) is missing.
    static Result<std::unique_ptr<VulkanContext>> create(const ContextOptions& options);
    // Loads the libraries a context with these options uses (the Vulkan loader, every driver,
    // the layers) and keeps them loaded for the life of the process, creating an instance and
    // destroying it again but no device. A process forked afterwards (core/fork_server.hpp)
    // starts with them loaded and relocated: on lavapipe, relocating LLVM and the validation
    // layer against the 260 libraries OpenImageIO brings is most of a short case's start.
    static Result<void> preload_libraries(const ContextOptions& options);
    // Whether the Khronos validation layer's library is loaded in this process (by a context
    // made with validation, or preloaded): a context made without validation does not unload
    // it, so a process that must run without the layer checks this.
    static bool validation_layer_loaded();
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical_device() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return queue_family_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    std::string device_name() const { return properties_.deviceName; }
    VkFormat stencil_format() const { return stencil_format_; }
    PFN_vkCmdPushDescriptorSetKHR push_descriptor_fn() const { return push_descriptor_; }

    // Records commands with `record` into a fresh command buffer, submits and waits.
    Result<void> submit_and_wait(const std::function<void(VkCommandBuffer)>& record);

    // Finds a memory type allowed by `type_bits` that has all of `flags`.
    Result<uint32_t> find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const;

    // Validation messages (warnings and errors) seen since creation; tests require none.
    const std::vector<std::string>& validation_messages() const { return messages_; }
    // Validation messages seen by every context of this process, including those reported
    // while a context is destroyed (leaked objects are reported by vkDestroyDevice).
    static uint64_t process_validation_message_count();
    bool validation_enabled() const { return validation_; }

    ResourceCounters& counters() { return counters_; }
    const ResourceCounters& counters() const { return counters_; }

  private:
    VulkanContext() = default;
    Result<void> create_instance(const ContextOptions& options);
    Result<void> pick_device(const std::string& selector);
    Result<void> create_device();

    static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkFormat stencil_format_ = VK_FORMAT_UNDEFINED;
    PFN_vkCmdPushDescriptorSetKHR push_descriptor_ = nullptr;
    bool validation_ = false;
    std::vector<std::string> messages_;
    ResourceCounters counters_;
};

}  // namespace acetate
