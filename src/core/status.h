#pragma once

#include <optional>
#include <string>
#include <utility>
#include <variant>

#include "core/check.h"

namespace semchain {

// The outcome of an operation a user can make fail (bad file, bad option, bad log line).
// The message is one line that names the file, line or key and what is wrong.
class Status {
 public:
  Status() = default;
  static Status Ok() { return Status(); }
  static Status Error(std::string message) { return Status(std::move(message)); }

  bool ok() const { return !message_.has_value(); }
  const std::string& message() const {
    SEMCHAIN_CHECK(!ok());
    return *message_;
  }
  // Returns this error with 'context: ' put in front, e.g. the file name.
  Status WithContext(const std::string& context) const {
    return ok() ? *this : Status(context + ": " + *message_);
  }

 private:
  explicit Status(std::string message) : message_(std::move(message)) {}
  std::optional<std::string> message_;
};

// Either a value or an error Status.
template <typename T>
class Result {
 public:
  Result(T value) : data_(std::move(value)) {}      // NOLINT: implicit by design.
  Result(Status error) : data_(std::move(error)) {  // NOLINT: implicit by design.
    SEMCHAIN_CHECK(!std::get<Status>(data_).ok());
  }

  bool ok() const { return std::holds_alternative<T>(data_); }
  Status status() const { return ok() ? Status::Ok() : std::get<Status>(data_); }
  const T& value() const& {
    SEMCHAIN_CHECK(ok());
    return std::get<T>(data_);
  }
  T& value() & {
    SEMCHAIN_CHECK(ok());
    return std::get<T>(data_);
  }
  T&& value() && {
    SEMCHAIN_CHECK(ok());
    return std::get<T>(std::move(data_));
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

 private:
  std::variant<T, Status> data_;
};

}  // namespace semchain

// Returns early from a function returning Status or Result<T> when 'expr' failed.
#define SEMCHAIN_RETURN_IF_ERROR(expr)                   \
  do {                                                   \
    ::semchain::Status semchain_status_ = (expr);        \
    if (!semchain_status_.ok()) return semchain_status_; \
  } while (false)
