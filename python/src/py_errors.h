// scansurf Python: a library Error raised as the Python exception of its category
// (scansurf.InvalidInput, scansurf.ResourceLimit, ...; scansurf/_errors.py defines them).
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <utility>

#include "scansurf/result.h"

namespace scansurf::python {

// Raises the error's class with its message; never returns.
[[noreturn]] void raise(const Error& error);

// The value of a Result, or the Python exception of its error.
template <typename T>
T valueOrRaise(Result<T> result) {
  if (!result) raise(result.error());
  return std::move(result).value();
}
inline void valueOrRaise(Result<void> result) {
  if (!result) raise(result.error());
}

// An option the caller got wrong, raised as scansurf.InvalidArgument.
[[noreturn]] inline void raiseInvalidArgument(std::string message) { raise({Errc::InvalidArgument, std::move(message)}); }

}  // namespace scansurf::python
