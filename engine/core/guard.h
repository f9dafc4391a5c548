// scansurf: the API boundary. Nothing throws across the public API: a call that could throw
// (std::bad_alloc from a large allocation, or a library's exception) runs inside guarded(),
// which turns the exception into an Error saying what was being done.
#pragma once

#include <exception>
#include <new>
#include <string>

#include "scansurf/result.h"

namespace scansurf {

// Runs body() (returning a Result) and returns its result, or an Error for an exception:
// Errc::OutOfMemory for std::bad_alloc and std::length_error, Errc::Internal for the rest.
// `what` names the work, e.g. "scan conversion of 30 features on 512 x 350 x 202 voxels".
template <typename Body>
auto guarded(const std::string& what, Body&& body) noexcept -> decltype(body()) {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return makeError(Errc::OutOfMemory, "out of memory during " + what);
  } catch (const std::length_error&) {
    return makeError(Errc::OutOfMemory, "out of memory during " + what + " (a size beyond what can be allocated)");
  } catch (const std::exception& e) {
    return makeError(Errc::Internal, "unexpected failure during " + what + ": " + e.what());
  } catch (...) {
    return makeError(Errc::Internal, "unexpected failure during " + what);
  }
}

}  // namespace scansurf
