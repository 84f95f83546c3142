#pragma once
// acetate::host::Result<T>: how every call of the embedding API (acetate/host/host.hpp) reports
// failure. Nothing in the API throws: a call that can fail returns a Result holding either its
// value or an Error, whose message is one line naming the file, field or plugin at fault (the
// same line the `acetate` CLI prints). Self-contained: this header needs only the standard
// library.

#include <cassert>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace acetate::host {

// What kind of failure, for a program that acts on it (a message is for people).
enum class ErrorCode {
    InvalidInput,   // a scene file, field, argument or parameter is malformed or refused
    FileNotFound,   // a named file does not exist
    ImageDecode,    // an image could not be read
    ImageEncode,    // an image could not be written
    Io,             // another file-system failure
    VulkanInit,     // the Vulkan instance or device could not be created
    NoDevice,       // no Vulkan device matches the request
    DeviceLimit,    // the request exceeds what the device allows (an image size)
    OutOfMemory,    // a device allocation failed
    ShaderCompile,  // an effect's shader did not compile
    VulkanCall,     // another Vulkan call failed
    PluginRefused,  // the load policy refused a plugin (not VALIDATED for its exact binary)
};

struct Error {
    std::string message;  // one line, no trailing newline
    ErrorCode code = ErrorCode::InvalidInput;
    // What it concerns, for a program to build its interface from (the message names the same
    // for people); each empty where it concerns none. The scene (or other) file read; the field
    // in it, as the message writes it ("floors[1].effects[0].params.day", "canvas"); the id of
    // the plugin whose effect it concerns; that effect's floor (none for a global effect).
    std::string file, field, plugin;
    std::optional<uint32_t> floor;
};

template <class T>
class [[nodiscard]] Result {
  public:
    Result(T value) : state_(std::move(value)) {}
    Result(Error error) : state_(std::move(error)) {}

    bool ok() const { return state_.index() == 0; }
    explicit operator bool() const { return ok(); }

    // Only when ok(); asserted in debug builds.
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
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    // Only when !ok().
    const Error& error() const {
        assert(!ok());
        return std::get<1>(state_);
    }

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

}  // namespace acetate::host
