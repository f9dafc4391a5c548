// scansurf Python: contour sets read from files or made from Python polygons, checked by the
// same validation as files (scansurf/input.h).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "py_errors.h"
#include "py_types.h"

namespace scansurf::python {
namespace py = pybind11;
namespace {

// A path as Python's os functions give it: bytes that are not UTF-8 as surrogate escapes, so
// that the name opens the same file again (a plain str cast raised UnicodeDecodeError).
py::str fileName(const std::string& path) {
  return py::reinterpret_steal<py::str>(PyUnicode_DecodeFSDefaultAndSize(path.data(), static_cast<Py_ssize_t>(path.size())));
}

std::shared_ptr<PyContours> read(const std::filesystem::path& path, const std::filesystem::path& reference,
                                 const std::vector<std::string>& rois, const std::vector<std::string>& objects) {
  ReadOptions options;
  options.roiPatterns = rois;
  options.objectPatterns = objects;
  options.referenceSeries = reference;
  Result<ContourSet> contours = [&] {
    py::gil_scoped_release unlocked;
    return readContours(path, options);
  }();
  return std::make_shared<PyContours>(PyContours{valueOrRaise(std::move(contours)), path.string(), reference.string()});
}

// One polygon from anything numpy reads as an (N, 2) array of numbers.
Contour polygonOf(const py::handle& polygon, const std::string& where) {
  const auto points = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(polygon);
  if (!points || points.ndim() != 2 || points.shape(1) != 2)
    raiseInvalidArgument(where + ": a contour must be an (N, 2) array of x, y");
  Contour contour;
  const auto xy = points.unchecked<2>();
  for (py::ssize_t i = 0; i < xy.shape(0); ++i) contour.points.push_back({xy(i, 0), xy(i, 1)});
  return contour;
}

// A feature's slices: a mapping z -> polygons, or a sequence of (z, polygons).
std::vector<FeatureSlice> slicesOf(const py::handle& slices, const std::string& name) {
  const py::object items = py::isinstance<py::dict>(slices) ? slices.attr("items")() : py::reinterpret_borrow<py::object>(slices);
  std::vector<FeatureSlice> out;
  for (const py::handle item : items) {
    const auto pair = item.cast<py::tuple>();
    if (pair.size() != 2) raiseInvalidArgument("feature \"" + name + "\": each slice is (z, [contour, ...])");
    FeatureSlice slice{pair[0].cast<double>(), {}};
    const std::string where = "feature \"" + name + "\", slice z = " + std::to_string(slice.z);
    for (const py::handle polygon : pair[1]) slice.contours.push_back(polygonOf(polygon, where));
    out.push_back(std::move(slice));
  }
  return out;
}

// features: a list of (name, colour or None, slices), validated as a file's would be.
std::shared_ptr<PyContours> fromPython(const py::list& features, const std::string& units, const std::string& source) {
  ContourSet set;
  set.source = source;
  set.units = units;
  for (const py::handle f : features) {
    const auto entry = f.cast<py::tuple>();
    Feature feature;
    feature.name = entry[0].cast<std::string>();
    if (!entry[1].is_none()) feature.color = entry[1].cast<Rgb>();
    feature.slices = slicesOf(entry[2], feature.name);
    set.features.push_back(std::move(feature));
  }
  valueOrRaise(validateContours(set));
  return std::make_shared<PyContours>(PyContours{std::move(set), source, {}});
}

py::list slicesAsArrays(const Feature& feature) {
  py::list out;
  for (const FeatureSlice& slice : feature.slices) {
    py::list polygons;
    for (const Contour& c : slice.contours) {
      py::array_t<double> points({static_cast<py::ssize_t>(c.points.size()), py::ssize_t{2}});
      auto xy = points.mutable_unchecked<2>();
      for (std::size_t i = 0; i < c.points.size(); ++i) xy(i, 0) = c.points[i].x, xy(i, 1) = c.points[i].y;
      polygons.append(points);
    }
    out.append(py::make_tuple(slice.z, polygons));
  }
  return out;
}

}  // namespace

void registerContours(py::module_& m) {
  py::class_<PyContours, std::shared_ptr<PyContours>>(m, "ContourSet")
      .def_property_readonly("source", [](const PyContours& c) { return fileName(c.set.source); })
      .def_property_readonly("input", [](const PyContours& c) { return fileName(c.input); })
      .def_property_readonly("reference", [](const PyContours& c) { return c.referenceSeries; })
      .def_property_readonly("units", [](const PyContours& c) { return c.set.units; })
      .def_property_readonly("names",
                             [](const PyContours& c) {
                               std::vector<std::string> names;
                               for (const Feature& f : c.set.features) names.push_back(f.name);
                               return names;
                             })
      .def_property_readonly("warnings", [](const PyContours& c) { return c.set.warnings; })
      .def_property_readonly("notes", [](const PyContours& c) { return c.set.notes; })
      .def("__len__", [](const PyContours& c) { return c.set.features.size(); })
      .def(
          "_slices", [](const PyContours& c, std::size_t i) { return slicesAsArrays(c.set.features.at(i)); }, py::arg("feature"))
      .def("_colors", [](const PyContours& c) { return featureColors(c.set); })
      .def(
          "write_json", [](const PyContours& c, const std::filesystem::path& path) { valueOrRaise(writeContours(c.set, path)); },
          py::arg("path"), "Writes the set as contour-set JSON (docs/input-format.md).");
  m.def("_read", &read, py::arg("path"), py::arg("reference"), py::arg("rois"), py::arg("objects"));
  m.def("_contours", &fromPython, py::arg("features"), py::arg("units"), py::arg("source"));
  m.def("_file_stems", [](const std::vector<std::string>& names) {
    std::vector<std::string> used, out;
    for (const std::string& n : names) out.push_back(fileStem(n, used));
    return out;
  });
  m.def("_detect_format", [](const std::filesystem::path& p) { return std::string(inputFormatName(detectInputFormat(p))); });
}

}  // namespace scansurf::python
