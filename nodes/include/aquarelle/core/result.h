// Errors as values at module boundaries: Result<T> holds a T or an Error with a message that
// says what went wrong, where, and how to fix it.
#pragma once

#include <aquarelle/core/message_text.h>

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace aq {

struct Error {
  std::string message;
};

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : data_(std::move(value)) {}      // NOLINT(google-explicit-constructor)
  Result(Error error) : data_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return std::holds_alternative<T>(data_); }
  explicit operator bool() const { return ok(); }
  T& value() & { return std::get<T>(data_); }
  const T& value() const& { return std::get<T>(data_); }
  T&& value() && { return std::get<T>(std::move(data_)); }
  T* operator->() { return &std::get<T>(data_); }
  const T* operator->() const { return &std::get<T>(data_); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  const Error& error() const { return std::get<Error>(data_); }
  const std::string& message() const { return error().message; }

 private:
  std::variant<T, Error> data_;
};

struct Ok {};
using Status = Result<Ok>;

// Messages are one line: control characters in them (a path or a name holding a newline or
// an ESC sequence) are escaped; a trailing newline is dropped.
inline Error make_error(std::string message) {
  while (!message.empty() && message.back() == '\n') message.pop_back();
  return Error{escape_for_message(message)};
}

// For the few messages made of several lines on purpose (a shader's compile log, every
// backend's failure, a file's list of problems): control characters other than newlines are
// escaped.
inline Error make_error_lines(std::string message) {
  while (!message.empty() && message.back() == '\n') message.pop_back();
  return Error{escape_for_message(message, true)};
}

}  // namespace aq
