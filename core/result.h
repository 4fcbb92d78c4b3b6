#pragma once
// Result<T>: data and I/O failures travel as values (cesium-native style); contract violations
// are asserts. C++20 has no std::expected, so this is the small subset vegstream needs.

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace vegstream {

// What kind of failure, so the command line can map user mistakes to exit code 2.
enum class ErrorKind {
  InvalidInput,  // the user gave something wrong: bad file, field, option value
  NotFound,      // a file, device or tile that does not exist
  Unsupported,   // valid input that vegstream cannot handle (a CRS, a format)
  Io,            // the operating system failed to read or write
  Gpu,           // the graphics driver failed
  Internal,      // a bug: should never reach a user
};

struct Error {
  ErrorKind kind = ErrorKind::Internal;
  std::string message;  // one sentence naming the file/field and the problem

  // True for mistakes the user can fix (exit code 2 on the command line).
  bool isUserError() const {
    return kind == ErrorKind::InvalidInput || kind == ErrorKind::NotFound || kind == ErrorKind::Unsupported;
  }
};

inline Error makeError(ErrorKind kind, std::string message) { return Error{kind, std::move(message)}; }

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : data_(std::move(value)) {}      // NOLINT: implicit by design
  Result(Error error) : data_(std::move(error)) {}  // NOLINT: implicit by design

  bool ok() const { return data_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & {
    assert(ok());
    return std::get<0>(data_);
  }
  const T& value() const& {
    assert(ok());
    return std::get<0>(data_);
  }
  T&& value() && {
    assert(ok());
    return std::get<0>(std::move(data_));
  }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  const Error& error() const {
    assert(!ok());
    return std::get<1>(data_);
  }

 private:
  std::variant<T, Error> data_;
};

// Result<void>: success or an Error.
template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit by design
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

using Status = Result<void>;

}  // namespace vegstream
