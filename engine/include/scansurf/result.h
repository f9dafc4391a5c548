// scansurf: Result<T>, the error type returned at every module edge.
// A subset of C++23's std::expected<T, Error>, spelled the same (has_value, value, error,
// operator bool, *, ->, value_or), so code written against it reads as std::expected code.
// Unlike std::expected, value() on an error is undefined behaviour rather than a throw (no
// exception crosses the API), and takeError() moves the error out for returning it upward:
// `return std::move(r).takeError();` is std::expected's `return std::unexpected(r.error());`.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace scansurf {

// Error categories; the command-line tool maps each to an exit code (docs/limits.md).
enum class Errc {
  InvalidArgument = 1,   // an option or parameter out of range
  InvalidInput = 2,      // the input file is malformed or inconsistent
  Io = 3,                // a file could not be read or written
  NoDevice = 4,          // no usable Vulkan device
  Vulkan = 5,            // a Vulkan call failed
  Internal = 6,          // a broken invariant: a bug in scansurf
  OutOfMemory = 7,       // a host or device allocation failed; the message names what and how much
  ResourceLimit = 8,     // refused before starting: the run would need more memory than allowed
  DefectiveSurface = 9,  // a surface came out open, not manifold or not oriented (scansurf/audit.h)
};

// A short lower-case name of the category ("invalid argument", "out of memory", ...).
inline const char* errcName(Errc code) noexcept {
  switch (code) {
    case Errc::InvalidArgument: return "invalid argument";
    case Errc::InvalidInput: return "invalid input";
    case Errc::Io: return "I/O error";
    case Errc::NoDevice: return "no usable Vulkan device";
    case Errc::Vulkan: return "Vulkan error";
    case Errc::Internal: return "internal error";
    case Errc::OutOfMemory: return "out of memory";
    case Errc::ResourceLimit: return "resource limit";
    case Errc::DefectiveSurface: return "defective surface";
  }
  return "error";
}

struct Error {
  Errc code = Errc::Internal;
  std::string message;
};

// The error half of a Result, convertible to any Result<T>.
struct Unexpected {
  Error error;
};

inline Unexpected makeError(Errc code, std::string message) { return Unexpected{Error{code, std::move(message)}}; }

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}
  Result(Unexpected e) : state_(std::move(e.error)) {}

  bool has_value() const { return state_.index() == 0; }
  explicit operator bool() const { return has_value(); }

  T& value() & { return std::get<0>(state_); }
  const T& value() const& { return std::get<0>(state_); }
  T&& value() && { return std::get<0>(std::move(state_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  template <typename U>
  T value_or(U&& fallback) const& {
    return has_value() ? value() : static_cast<T>(std::forward<U>(fallback));
  }

  const Error& error() const { return std::get<1>(state_); }
  Unexpected takeError() && { return Unexpected{std::get<1>(std::move(state_))}; }

 private:
  std::variant<T, Error> state_;
};

template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Unexpected e) : error_(std::move(e.error)), failed_(true) {}

  bool has_value() const { return !failed_; }
  explicit operator bool() const { return !failed_; }
  const Error& error() const { return error_; }
  Unexpected takeError() && { return Unexpected{std::move(error_)}; }

 private:
  Error error_;
  bool failed_ = false;
};

}  // namespace scansurf

#define SCANSURF_CONCAT_INNER(a, b) a##b
#define SCANSURF_CONCAT(a, b) SCANSURF_CONCAT_INNER(a, b)

// Evaluates a Result-returning expression; on error returns the error from the caller.
#define SCANSURF_TRY(expr)                                                     \
  do {                                                                         \
    auto scansurfTryResult_ = (expr);                                          \
    if (!scansurfTryResult_) return std::move(scansurfTryResult_).takeError(); \
  } while (false)

// `SCANSURF_ASSIGN_OR_RETURN(auto x, f());` declares x from f()'s value or returns its error.
#define SCANSURF_ASSIGN_OR_RETURN(lhs, expr) SCANSURF_ASSIGN_OR_RETURN_IMPL(SCANSURF_CONCAT(scansurfResult_, __LINE__), lhs, expr)
#define SCANSURF_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                                   \
  if (!tmp) return std::move(tmp).takeError();         \
  lhs = std::move(tmp).value()
