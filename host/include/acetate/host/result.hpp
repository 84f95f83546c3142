#pragma once
// acetate::host::Result<T>: how every call of the embedding API (acetate/host/host.hpp) reports
// failure. Nothing in the API throws: a call that can fail returns a Result holding either its
// value or an Error, whose message is one line naming the file, field or plugin at fault (the
// same line the `acetate` CLI prints). Self-contained: this header needs only the standard
// library.

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace acetate::host {

struct Error {
    std::string message;  // one line, no trailing newline
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
