#include "core/result.hpp"

namespace acetate {

const char* to_string(ErrorCode code) {
    switch (code) {
        case ErrorCode::InvalidInput:
            return "invalid input";
        case ErrorCode::FileNotFound:
            return "file not found";
        case ErrorCode::ImageDecode:
            return "image decode";
        case ErrorCode::ImageEncode:
            return "image encode";
        case ErrorCode::Io:
            return "i/o";
        case ErrorCode::VulkanInit:
            return "vulkan init";
        case ErrorCode::NoDevice:
            return "no device";
        case ErrorCode::DeviceLimit:
            return "device limit";
        case ErrorCode::OutOfMemory:
            return "out of memory";
        case ErrorCode::ShaderCompile:
            return "shader compile";
        case ErrorCode::VulkanCall:
            return "vulkan call";
        case ErrorCode::PluginRefused:
            return "plugin refused";
    }
    return "unknown";
}

}  // namespace acetate
