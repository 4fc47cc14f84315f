// Status and Result<T>: how fleetmap reports errors in outside data (files, telegrams,
// network messages) without exceptions and without aborting. Modelled on absl::StatusOr,
// kept small because C++17 has no std::expected.
#pragma once

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace fleetmap::core {

enum class StatusCode {
  kOk = 0,
  kInvalidArgument,     // the input is malformed or out of range
  kDataLoss,            // bytes are corrupt: bad checksum, truncated, undecompressable
  kOutOfRange,          // a size or index exceeds a configured limit
  kNotFound,            // a file or key does not exist
  kIoError,             // the operating system refused a read or write
  kUnimplemented,       // a valid but unsupported variant (a newer format version)
  kFailedPrecondition,  // the input is valid but does not fit the current state
};

const char* StatusCodeName(StatusCode code);

class Status {
 public:
  Status() = default;  // ok
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  // "DATA_LOSS: codec frame CRC mismatch" style text for logs and error output.
  std::string ToString() const;
  // Returns a copy whose message is prefixed with `context` ("map.yaml: ...").
  Status WithContext(const std::string& context) const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status OkStatus() { return Status(); }
inline Status InvalidArgument(std::string m) {
  return {StatusCode::kInvalidArgument, std::move(m)};
}
inline Status DataLoss(std::string m) { return {StatusCode::kDataLoss, std::move(m)}; }
inline Status OutOfRange(std::string m) { return {StatusCode::kOutOfRange, std::move(m)}; }
inline Status NotFound(std::string m) { return {StatusCode::kNotFound, std::move(m)}; }
inline Status IoError(std::string m) { return {StatusCode::kIoError, std::move(m)}; }
inline Status Unimplemented(std::string m) { return {StatusCode::kUnimplemented, std::move(m)}; }
inline Status FailedPrecondition(std::string m) {
  return {StatusCode::kFailedPrecondition, std::move(m)};
}

// Either a value or a non-ok Status. Accessing the value of an error is a programming
// error (assert), so callers check ok() first.
template <typename T>
class Result {
 public:
  Result(T value) : data_(std::move(value)) {}        // NOLINT: implicit like StatusOr
  Result(Status status) : data_(std::move(status)) {  // NOLINT
    assert(!std::get<Status>(data_).ok() && "Result needs a value or an error");
  }

  bool ok() const { return std::holds_alternative<T>(data_); }
  const Status& status() const {
    static const Status kOk;
    return ok() ? kOk : std::get<Status>(data_);
  }
  const T& value() const& {
    assert(ok());
    return std::get<T>(data_);
  }
  T& value() & {
    assert(ok());
    return std::get<T>(data_);
  }
  T&& value() && {
    assert(ok());
    return std::get<T>(std::move(data_));
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

 private:
  std::variant<T, Status> data_;
};

}  // namespace fleetmap::core

// Returns the status from the enclosing function when `expr` (a Status) is not ok.
#define FLEETMAP_RETURN_IF_ERROR(expr)                   \
  do {                                                   \
    ::fleetmap::core::Status fleetmap_status_ = (expr);  \
    if (!fleetmap_status_.ok()) return fleetmap_status_; \
  } while (0)

// Declares nothing: assigns the value of `expr` (a Result) to `lhs`, or returns its status.
#define FLEETMAP_ASSIGN_OR_RETURN(lhs, expr)                      \
  do {                                                            \
    auto fleetmap_result_ = (expr);                               \
    if (!fleetmap_result_.ok()) return fleetmap_result_.status(); \
    lhs = std::move(fleetmap_result_).value();                    \
  } while (0)
