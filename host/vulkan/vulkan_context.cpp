#include "vulkan/vulkan_context.hpp"

#include <dlfcn.h>
#include <fmt/format.h>
#include <link.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>

#include "vulkan/vk_check.hpp"

namespace acetate {
namespace {

const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

bool layer_available(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

int device_type_rank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return 3;
        default:
            return 4;
    }
}

std::atomic<uint64_t> g_validation_messages{0};

// The file names of every object loaded in the process now.
std::set<std::string> loaded_objects() {
    std::set<std::string> names;
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void* out) {
            if (info->dlpi_name && info->dlpi_name[0])
                static_cast<std::set<std::string>*>(out)->insert(info->dlpi_name);
            return 0;
        },
        &names);
    return names;
}

}  // namespace

uint64_t VulkanContext::process_validation_message_count() {
    return g_validation_messages.load();
}

ContextOptions ContextOptions::from_environment() {
    ContextOptions options;
    if (const char* v = std::getenv("ACETATE_VALIDATION"))
        options.validation = std::string(v) == "1";
    if (const char* d = std::getenv("ACETATE_DEVICE")) options.device_selector = d;
    return options;
}

Result<std::unique_ptr<VulkanContext>> VulkanContext::create(const ContextOptions& options) {
    std::unique_ptr<VulkanContext> context(new VulkanContext());
    ACETATE_TRY(context->create_instance(options));
    ACETATE_TRY(context->pick_device(options.device_selector));
    ACETATE_TRY(context->create_device());
    return context;
}

Result<void> VulkanContext::preload_libraries(const ContextOptions& options) {
    const std::set<std::string> before = loaded_objects();
    std::unique_ptr<VulkanContext> probe(new VulkanContext());
    ACETATE_TRY(probe->create_instance(options));
    // One more reference to each object the instance loaded, never released: destroying the
    // instance unloads them otherwise.
    for (const std::string& name : loaded_objects())
        if (!before.count(name)) (void)dlopen(name.c_str(), RTLD_LAZY | RTLD_NOLOAD);
    probe.reset();
    if (const uint64_t messages = process_validation_message_count())
        return make_error(ErrorCode::VulkanInit,
                          fmt::format("{} validation message{} while preloading Vulkan", messages,
                                      messages == 1 ? "" : "s"));
    return {};
}

bool VulkanContext::validation_layer_loaded() {
    for (const std::string& name : loaded_objects())
        if (name.find("libVkLayer_khronos_validation") != std::string::npos) return true;
    return false;
}

VulkanContext::~VulkanContext() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        if (fence_) vkDestroyFence(device_, fence_, nullptr);
        if (command_pool_) vkDestroyCommandPool(device_, command_pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanContext::on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
    ++g_validation_messages;
    auto* self = static_cast<VulkanContext*>(user);
    self->messages_.emplace_back(data->pMessage ? data->pMessage : "(no message)");
    std::fprintf(stderr, "acetate: vulkan validation: %s\n", self->messages_.back().c_str());
    return VK_FALSE;
}

Result<void> VulkanContext::create_instance(const ContextOptions& options) {
    validation_ = options.validation;
    if (validation_ && !layer_available(kValidationLayer))
        return make_error(ErrorCode::VulkanInit,
                          fmt::format("ACETATE_VALIDATION=1 but {} is not installed "
                                      "(Debian package vulkan-validationlayers)",
                                      kValidationLayer));

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "acetate";
    app.pEngineName = "acetate";
    app.apiVersion = VK_API_VERSION_1_3;

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    VkDebugUtilsMessengerCreateInfoEXT messenger_info{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger_info.pfnUserCallback = &VulkanContext::on_validation_message;
    messenger_info.pUserData = this;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    if (validation_) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        info.pNext = &messenger_info;  // also catches messages from vkCreate/DestroyInstance
    }
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkResult r = vkCreateInstance(&info, nullptr, &instance_);
    if (r != VK_SUCCESS)
        return make_error(ErrorCode::VulkanInit,
                          fmt::format("vkCreateInstance failed (VkResult {}); is a Vulkan driver "
                                      "installed (Debian package mesa-vulkan-drivers)?",
                                      int(r)),
                          r);
    if (validation_) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create) return make_error(ErrorCode::VulkanInit, "VK_EXT_debug_utils is missing");
        ACETATE_VK(create(instance_, &messenger_info, nullptr, &messenger_));
    }
    return {};
}

Result<void> VulkanContext::pick_device(const std::string& selector) {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance_, &count, devices.data());
    if (devices.empty()) return make_error(ErrorCode::NoDevice, "no Vulkan device found");

    std::vector<std::string> names;
    for (auto d : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        names.emplace_back(p.deviceName);
    }
    int chosen = -1;
    if (!selector.empty()) {
        uint64_t index = 0;
        const auto [end, error] =
            std::from_chars(selector.data(), selector.data() + selector.size(), index);
        const bool numeric = error == std::errc() && end == selector.data() + selector.size();
        for (size_t i = 0; i < devices.size() && chosen < 0; ++i) {
            if (numeric ? index == i : lower(names[i]).find(lower(selector)) != std::string::npos)
                chosen = int(i);
        }
        if (chosen < 0) {
            std::string all;
            for (size_t i = 0; i < names.size(); ++i)
                all += fmt::format("{}[{}] {}", i ? ", " : "", i, names[i]);
            return make_error(
                ErrorCode::NoDevice,
                fmt::format("ACETATE_DEVICE=\"{}\" matches no device; have {}", selector, all));
        }
    } else {
        int best_rank = 99;
        for (size_t i = 0; i < devices.size(); ++i) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(devices[i], &p);
            if (device_type_rank(p.deviceType) < best_rank) {
                best_rank = device_type_rank(p.deviceType);
                chosen = int(i);
            }
        }
    }
    physical_ = devices[size_t(chosen)];
    vkGetPhysicalDeviceProperties(physical_, &properties_);
    if (VK_API_VERSION_MINOR(properties_.apiVersion) < 3 &&
        VK_API_VERSION_MAJOR(properties_.apiVersion) == 1)
        return make_error(
            ErrorCode::VulkanInit,
            fmt::format("device \"{}\" supports Vulkan {}.{}; Acetate needs 1.3",
                        properties_.deviceName, VK_API_VERSION_MAJOR(properties_.apiVersion),
                        VK_API_VERSION_MINOR(properties_.apiVersion)));
    return {};
}

Result<void> VulkanContext::create_device() {
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &family_count, families.data());
    bool found = false;
    for (uint32_t i = 0; i < family_count; ++i) {
        if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
            queue_family_ = i;
            found = true;
            break;
        }
    }
    if (!found)
        return make_error(ErrorCode::VulkanInit,
                          fmt::format("device \"{}\" has no graphics queue", device_name()));

    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &f13;
    vkGetPhysicalDeviceFeatures2(physical_, &f2);
    if (!f13.dynamicRendering || !f13.synchronization2 || !f2.features.fragmentStoresAndAtomics)
        return make_error(ErrorCode::VulkanInit,
                          fmt::format("device \"{}\" lacks dynamicRendering, synchronization2 or "
                                      "fragmentStoresAndAtomics",
                                      device_name()));

    // Stencil-only formats are optional in Vulkan; take the first the device can attach.
    for (VkFormat f :
         {VK_FORMAT_S8_UINT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D32_SFLOAT_S8_UINT}) {
        VkFormatProperties props;
        vkGetPhysicalDeviceFormatProperties(physical_, f, &props);
        if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) {
            stencil_format_ = f;
            break;
        }
    }
    if (stencil_format_ == VK_FORMAT_UNDEFINED)
        return make_error(ErrorCode::VulkanInit, "no stencil attachment format is supported");

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;

    VkPhysicalDeviceVulkan13Features enable13{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    enable13.dynamicRendering = VK_TRUE;
    enable13.synchronization2 = VK_TRUE;
    VkPhysicalDeviceFeatures2 enable{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    enable.pNext = &enable13;
    enable.features.fragmentStoresAndAtomics = VK_TRUE;

    const char* extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = &enable;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue_info;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = extensions;
    VkResult r = vkCreateDevice(physical_, &info, nullptr, &device_);
    if (r != VK_SUCCESS)
        return make_error(
            ErrorCode::VulkanInit,
            fmt::format("vkCreateDevice on \"{}\" failed (VkResult {})", device_name(), int(r)), r);
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
    push_descriptor_ = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
    if (!push_descriptor_)
        return make_error(ErrorCode::VulkanInit, "VK_KHR_push_descriptor is missing");

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    ACETATE_VK(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_));
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    ACETATE_VK(vkCreateFence(device_, &fence_info, nullptr, &fence_));
    return {};
}

Result<void> VulkanContext::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = command_pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ACETATE_VK(vkAllocateCommandBuffers(device_, &alloc, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd, &begin);
    record(cmd);
    // The host reads results (readbacks, violation counters) after the fence: make every
    // device write available to host reads.
    VkMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    to_host.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    to_host.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &to_host;
    vkCmdPipelineBarrier2(cmd, &dependency);
    ++counters_.barriers_recorded;
    vkEndCommandBuffer(cmd);

    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VkResult r = vkQueueSubmit(queue_, 1, &submit, fence_);
    if (r == VK_SUCCESS) r = vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX);
    vkResetFences(device_, 1, &fence_);
    vkFreeCommandBuffers(device_, command_pool_, 1, &cmd);
    if (r != VK_SUCCESS) return vk_error("vkQueueSubmit/vkWaitForFences", r);
    return {};
}

Result<uint32_t> VulkanContext::find_memory_type(uint32_t type_bits,
                                                 VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(physical_, &mem);
    for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & flags) == flags)
            return i;
    return make_error(ErrorCode::OutOfMemory, "no suitable Vulkan memory type");
}

}  // namespace acetate
