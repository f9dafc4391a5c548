// scansurf Python: errors as Python exceptions (py_errors.h).
#include "py_errors.h"

namespace scansurf::python {
namespace py = pybind11;
namespace {

// The Python class of each category, by name in scansurf._errors.
const char* className(Errc code) {
  switch (code) {
    case Errc::InvalidArgument: return "InvalidArgument";
    case Errc::InvalidInput: return "InvalidInput";
    case Errc::Io: return "IoError";
    case Errc::NoDevice: return "NoDevice";
    case Errc::Vulkan: return "VulkanError";
    case Errc::Internal: return "InternalError";
    case Errc::OutOfMemory: return "OutOfMemory";
    case Errc::ResourceLimit: return "ResourceLimit";
    case Errc::DefectiveSurface: return "DefectiveSurface";
  }
  return "Error";
}

// The library names a refused option by its BuildOptions field; a Python user wrote a keyword.
std::string inKeywords(std::string message) {
  static constexpr std::pair<const char*, const char*> kKeywords[] = {
      {"option remeshing.edgeLength ", "option edge_length "},
      {"option smoothing.strength ", "option smooth_strength "},
      {"option smoothing.iterations ", "option smooth_iterations "},
      {"option smoothing.minAngle ", "option min_angle "},
      {"option smoothing.snap ", "option snap "},
      {"option simplification.tolerance ", "option simplify_tolerance "},
      {"option simplification.edgeLength ", "option simplify_edge_length "},
      {"option simplification.minAngle ", "option simplify_min_angle "},
      {"option interpolation.factor ", "option interpolate "}};
  for (const auto& [field, keyword] : kKeywords)
    if (message.rfind(field, 0) == 0) return keyword + message.substr(std::char_traits<char>::length(field));
  return message;
}

}  // namespace

void raise(const Error& error) {
  py::gil_scoped_acquire gil;
  const py::object cls = py::module_::import("scansurf._errors").attr(className(error.code));
  const py::str message(inKeywords(error.message));
  PyErr_SetObject(cls.ptr(), message.ptr());
  throw py::error_already_set();
}

}  // namespace scansurf::python
