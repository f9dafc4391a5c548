// scansurf Python: the C++ objects behind scansurf.ContourSet, scansurf.Engine and
// scansurf.BuildResult, and the functions that register each part of the module.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "scansurf/scansurf.h"

namespace scansurf::python {

// A validated contour set, with where it came from.
struct PyContours {
  ContourSet set;
  std::string input;            // the path it was read from, or its description
  std::string referenceSeries;  // the CT folder it was read with (DICOM SEG output), or empty
};

// One Vulkan device for any number of builds; builds on it are serialized (Engine is used by
// one thread at a time), builds on different engines run concurrently.
struct PyEngine {
  PyEngine(Engine e, bool v) : engine(std::move(e)), validation(v) {}
  Engine engine;
  bool validation = false;
  std::mutex mutex;
};

// A feature's surface with its own vertices (the shared mesh's, renumbered).
struct CompactSurface {
  std::vector<float> vertices;
  std::vector<std::uint32_t> faces;
};

// What build() gave back, with what the writers and the report need beside it. The numpy views
// of its arrays keep this object alive.
struct PyResult {
  std::shared_ptr<PyContours> contours;
  BuildResult built;
  BuildOptions options;  // as given (callbacks unset)
  DeviceInfo device;
  bool validation = false;
  std::string started;
  VolumeUnit volumeUnit;                                // of the report's volumes
  std::vector<std::optional<CompactSurface>> surfaces;  // per feature, when first asked for
  std::optional<LabelImage> labelImage;
  std::mutex mutex;  // guards the lazily made members

  const CompactSurface& surfaceOf(int feature);
  const LabelImage& image();
};

void registerContours(pybind11::module_& m);
void registerEngine(pybind11::module_& m);
void registerResult(pybind11::module_& m);

}  // namespace scansurf::python
