#pragma once
/// Errors as values for the control path (no exceptions there).
///
/// `Result<T>` holds either a T or an `Error`; `Status` is `Result<void>`.
/// Configuration and file loading may throw instead; `main` catches and prints.

#include <cassert>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace p3at {

/// What went wrong, as a category a caller can branch on and a message a
/// person can read. The message names the thing (URL, file, device) involved.
struct Error {
  enum class Code {
    invalid_argument,  ///< malformed URL, flag or parameter
    not_found,         ///< missing device, file or host
    refused,           ///< connection refused, device busy, permission denied
    timeout,           ///< nothing arrived in time
    closed,            ///< the peer closed the stream
    io,                ///< any other operating-system error
    protocol,          ///< the peer spoke something we do not understand
    state,             ///< the request is not allowed in the current state
  };
  Code code = Code::io;
  std::string message;
};

/// Human-readable name of an error code, for logs.
constexpr const char* to_string(Error::Code code) {
  switch (code) {
    case Error::Code::invalid_argument: return "invalid argument";
    case Error::Code::not_found: return "not found";
    case Error::Code::refused: return "refused";
    case Error::Code::timeout: return "timeout";
    case Error::Code::closed: return "closed";
    case Error::Code::io: return "i/o error";
    case Error::Code::protocol: return "protocol error";
    case Error::Code::state: return "not allowed now";
  }
  return "error";
}

inline Error make_error(Error::Code code, std::string message) { return Error{code, std::move(message)}; }

/// Either a value or an Error. Check `ok()` before `value()`.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : storage_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Result(Error error) : storage_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return std::holds_alternative<T>(storage_); }
  explicit operator bool() const { return ok(); }

  T& value() & { assert(ok()); return std::get<T>(storage_); }
  const T& value() const& { assert(ok()); return std::get<T>(storage_); }
  T&& value() && { assert(ok()); return std::get<T>(std::move(storage_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  const Error& error() const { assert(!ok()); return std::get<Error>(storage_); }

 private:
  std::variant<T, Error> storage_;
};

/// Success or an Error, with no value.
template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT(google-explicit-constructor)
  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const { assert(!ok_); return error_; }

 private:
  Error error_{};
  bool ok_ = true;
};

using Status = Result<void>;

}  // namespace p3at
