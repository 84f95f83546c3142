#pragma once
// Result<T>: how fallible host operations report failure caused by the environment or the
// input (tier 3 of docs/design.md, "Errors: three tiers"). Internal invariants use assert;
// contract violations use ACETATE_CHECK (core/check.hpp).

#include <cassert>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace acetate {

enum class ErrorCode {
    InvalidInput,   // a scene file, field or argument is malformed
    FileNotFound,   // a named file does not exist
    ImageDecode,    // OpenImageIO could not read an image
    ImageEncode,    // OpenImageIO could not write an image
    Io,             // other file-system failure
    VulkanInit,     // instance or device creation failed
    NoDevice,       // no Vulkan device matches the request
    DeviceLimit,    // the request exceeds what the device allows (e.g. image size)
    OutOfMemory,    // a Vulkan allocation failed
    ShaderCompile,  // glslang rejected a shader
    VulkanCall,     // any other Vulkan call failed
    PluginRefused,  // the load policy refused a plugin (not VALIDATED for its binary)
};

const char* to_string(ErrorCode code);

// One failure: what kind, the VkResult when Vulkan was involved (its value, 0 for none: core
// includes no Vulkan header, so the registry and the tools that never render do not link
// Vulkan), and a one-line message that names the file, field or object at fault.
struct Error {
    ErrorCode code = ErrorCode::InvalidInput;
    std::string message;
    int32_t vk_result = 0;
    // What the error concerns, for a program to act on (the message names them for people);
    // empty where it concerns none: the file read, the field in it
    // ("floors[1].effects[0].params.day"), the plugin's id, the floor.
    std::string file, field, plugin;
    std::optional<uint32_t> floor;
};

inline Error make_error(ErrorCode code, std::string message, int32_t vk = 0) {
    return Error{code, std::move(message), vk};
}

template <class T>
class [[nodiscard]] Result {
  public:
    Result(T value) : state_(std::move(value)) {}
    Result(Error error) : state_(std::move(error)) {}

    bool ok() const { return state_.index() == 0; }
    explicit operator bool() const { return ok(); }

    T& value() & {
        assert(ok());
        return std::get<0>(state_);
    }
    T&& value() && {
        assert(ok());
        return std::get<0>(std::move(state_));
    }
    const T& value() const& {
        assert(ok());
        return std::get<0>(state_);
    }
    const Error& error() const {
        assert(!ok());
        return std::get<1>(state_);
    }
    T* operator->() { return &value(); }
    T& operator*() { return value(); }

  private:
    std::variant<T, Error> state_;
};

template <>
class [[nodiscard]] Result<void> {
  public:
    Result() = default;
    Result(Error error) : error_(std::move(error)), ok_(false) {}
    bool ok() const { return ok_; }
    explicit operator bool() const { return ok_; }
    const Error& error() const {
        assert(!ok_);
        return error_;
    }

  private:
    Error error_;
    bool ok_ = true;
};

}  // namespace acetate

// Propagates an error from an expression returning Result<...>.
#define ACETATE_TRY(expr)                                                  \
    do {                                                                   \
        auto acetate_try_result_ = (expr);                                 \
        if (!acetate_try_result_.ok()) return acetate_try_result_.error(); \
    } while (0)
