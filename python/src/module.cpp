// scansurf Python: the extension module scansurf._scansurf, which the package scansurf
// (python/scansurf/__init__.py) wraps. Nothing of the library throws; each Error becomes the
// Python exception of its category (py_errors.h), never a crash of the interpreter.
#include <pybind11/pybind11.h>

#include "py_types.h"
#include "scansurf/version.h"

PYBIND11_MODULE(_scansurf, m) {
  m.doc() = "scansurf: separating surfaces from planar contours, on Vulkan (the compiled core)";
  m.attr("__version__") = scansurf::version();
  scansurf::python::registerContours(m);
  scansurf::python::registerEngine(m);
  scansurf::python::registerResult(m);
}
