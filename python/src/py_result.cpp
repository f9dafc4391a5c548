// scansurf Python: a build's results as numpy arrays viewed without copying (each view keeps
// the result alive), its report, and its files written as the command-line tool writes them.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <unordered_map>

#include "py_errors.h"
#include "py_types.h"

namespace scansurf::python {
namespace py = pybind11;
namespace fs = std::filesystem;

const CompactSurface& PyResult::surfaceOf(int feature) {
  const std::lock_guard<std::mutex> lock(mutex);
  auto& slot = surfaces.at(static_cast<std::size_t>(feature));
  if (slot) return *slot;
  CompactSurface s;
  std::unordered_map<std::uint32_t, std::uint32_t> renumbered;
  const std::vector<float>& positions = built.surfaces.mesh.positions;
  for (const std::uint32_t v : built.surfaces.features[static_cast<std::size_t>(feature)].triangles) {
    const auto [at, added] = renumbered.try_emplace(v, static_cast<std::uint32_t>(renumbered.size()));
    if (added) s.vertices.insert(s.vertices.end(), positions.begin() + 3 * v, positions.begin() + 3 * v + 3);
    s.faces.push_back(at->second);
  }
  slot = std::move(s);
  return *slot;
}

const LabelImage& PyResult::image() {
  const std::lock_guard<std::mutex> lock(mutex);
  if (!labelImage) labelImage = valueOrRaise(scansurf::labelImage(contours->set, built));
  return *labelImage;
}

namespace {

// A read-only view of `data` shaped `shape`, keeping `owner` alive.
template <typename T>
py::array view(const std::vector<T>& data, std::vector<py::ssize_t> shape, const py::object& owner) {
  py::array out(py::dtype::of<T>(), std::move(shape), {}, data.data(), owner);
  py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return out;
}

template <typename T>
py::ssize_t rows(const std::vector<T>& data, std::size_t width) {
  return static_cast<py::ssize_t>(data.size() / width);
}

py::tuple mesh(const py::object& self) {
  const MultiLabelMesh& m = self.cast<PyResult&>().built.surfaces.mesh;
  return py::make_tuple(view(m.positions, {rows(m.positions, 3), 3}, self), view(m.triangles, {rows(m.triangles, 3), 3}, self),
                        view(m.labels, {rows(m.labels, 2), 2}, self));
}

py::tuple surface(const py::object& self, int feature) {
  PyResult& r = self.cast<PyResult&>();
  if (feature < 0 || static_cast<std::size_t>(feature) >= r.surfaces.size())
    throw py::index_error("no feature " + std::to_string(feature));
  const CompactSurface* s = nullptr;
  {
    py::gil_scoped_release unlocked;
    s = &r.surfaceOf(feature);
  }
  return py::make_tuple(view(s->vertices, {rows(s->vertices, 3), 3}, self), view(s->faces, {rows(s->faces, 3), 3}, self));
}

py::dict stats(PyResult& r, int feature) {
  // Every build's audit computed the statistics of every feature.
  const std::vector<MeshStats>& all = r.built.audit.stats;
  if (feature < 0 || static_cast<std::size_t>(feature) >= all.size())
    throw py::index_error("no feature " + std::to_string(feature));
  const MeshStats* s = &all[static_cast<std::size_t>(feature)];
  const FeatureVolumes& v = r.built.overlaps.features[static_cast<std::size_t>(feature)];
  py::dict out;
  out["triangles"] = s->triangles, out["vertices"] = s->vertices, out["area"] = s->area, out["volume"] = s->volume;
  out["components"] = s->components, out["genus"] = s->genus, out["closed"] = s->closed, out["manifold"] = s->manifold;
  out["oriented"] = s->oriented, out["contour_volume"] = v.contour, out["voxel_volume"] = v.ownVolume;
  out["voxels"] = v.ownVoxels, out["layer"] = v.layer, out["mask_layer"] = v.maskLayer;
  return out;
}

py::tuple labelVolume(const py::object& self) {
  PyResult& r = self.cast<PyResult&>();
  const LabelImage* image = nullptr;
  {
    py::gil_scoped_release unlocked;
    image = &r.image();
  }
  const py::array labels = view(image->labels, {image->nz, image->ny, image->nx}, self);
  return py::make_tuple(labels, image->origin, image->axes, image->resampled, image->warnings);
}

// The report of the run, as the command-line tool's --report writes it.
RunReport reportOf(PyResult& r, const std::vector<std::vector<fs::path>>& files, std::vector<fs::path> outputs,
                   const SceneOptions& scene) {
  const RunSettings settings{r.options, scene, r.contours->referenceSeries, r.validation};
  ReportContext context{r.contours->input, runParameters(settings, r.built), r.built.timings, files, std::move(outputs)};
  context.started = r.started;
  context.volumeUnit = r.volumeUnit;
  return makeReport(r.contours->set, r.built, r.device, std::move(context));
}

std::string reportText(PyResult& r) {
  py::gil_scoped_release unlocked;
  return reportJson(reportOf(r, {}, {}, SceneOptions{}));
}

}  // namespace

namespace {

struct WriteRequest {
  fs::path dir;
  std::vector<std::string> formats;
  std::string sceneName;
  fs::path labelVolume, dicomSeg, report;
  bool draco = true;
};

OutputPlan planOf(const PyResult& r, const WriteRequest& w) {
  OutputPlan plan;
  plan.dir = w.dir;
  for (const std::string& f : w.formats) plan.formats.push_back(valueOrRaise(parseMeshFormat(f)));
  plan.sceneName = w.sceneName;
  plan.scene.draco = w.draco;
  plan.scene.opacity = displayOpacity(r.built.nesting);
  const auto inDir = [&](const fs::path& p) { return p.empty() || p.is_absolute() ? p : w.dir / p; };
  plan.labelVolume = inDir(w.labelVolume);
  plan.dicomSeg = inDir(w.dicomSeg);
  plan.referenceSeries = r.contours->referenceSeries;
  plan.report = inDir(w.report);
  return plan;
}

// Every output staged beside its destination and moved into place at once: a failure leaves
// nothing behind, and the report (last) is there only when everything else is.
Result<std::vector<fs::path>> writeAll(PyResult& r, const OutputPlan& plan) {
  SCANSURF_TRY(checkOutputs(plan));
  OutputStaging staging;
  for (const fs::path& dir : outputDirectories(plan)) SCANSURF_TRY(staging.lock(dir));
  SCANSURF_ASSIGN_OR_RETURN(SurfaceOutputs files, stageSurfaceOutputs(staging, plan, r.contours->set, r.built));
  if (!plan.report.empty()) {
    std::vector<fs::path> outputs = staging.targets();
    outputs.push_back(plan.report);
    RunReport report = reportOf(r, files.files, std::move(outputs), plan.scene);
    report.warnings.insert(report.warnings.end(), files.warnings.begin(), files.warnings.end());
    SCANSURF_TRY(staging.stage(plan.report, [&](const fs::path& p) { return writeReport(p, report); }));
  }
  return staging.commit();
}

std::vector<fs::path> write(PyResult& r, const WriteRequest& request) {
  const OutputPlan plan = planOf(r, request);
  Result<std::vector<fs::path>> written = [&] {
    py::gil_scoped_release unlocked;
    return writeAll(r, plan);
  }();
  return valueOrRaise(std::move(written));
}

py::list timings(const PyResult& r) {
  py::list out;
  for (const StageTime& t : r.built.timings) out.append(py::make_tuple(t.stage, t.seconds));
  return out;
}

py::dict gridDict(const Grid& g) {
  py::dict out;
  out["nx"] = g.nx, out["ny"] = g.ny, out["nz"] = g.nz, out["origin_x"] = g.originX, out["origin_y"] = g.originY;
  out["spacing_x"] = g.spacingX, out["spacing_y"] = g.spacingY, out["layer_z"] = g.layerZ;
  return out;
}

}  // namespace

void registerResult(py::module_& m) {
  py::class_<PyResult, std::shared_ptr<PyResult>>(m, "_BuildResult")
      .def_property_readonly("contours", [](const PyResult& r) { return r.contours; })
      .def_property_readonly("warnings", [](const PyResult& r) { return r.built.warnings; })
      .def_property_readonly("timings", &timings)
      .def_property_readonly("grid", [](const PyResult& r) { return gridDict(r.built.volume.grid); })
      .def_property_readonly("device", [](const PyResult& r) { return r.device.name; })
      .def_property_readonly("feature_count", [](const PyResult& r) { return r.built.surfaces.features.size(); })
      .def("_mesh", &mesh)
      .def("_surface", &surface, py::arg("feature"))
      .def("_stats", &stats, py::arg("feature"))
      .def("_label_volume", &labelVolume)
      .def("_report_json", &reportText)
      .def(
          "_write",
          [](PyResult& r, const fs::path& dir, const std::vector<std::string>& formats, const std::string& sceneName,
             const fs::path& labelVolume, const fs::path& dicomSeg, const fs::path& report, bool draco) {
            return write(r, {dir, formats, sceneName, labelVolume, dicomSeg, report, draco});
          },
          py::arg("dir"), py::arg("formats"), py::arg("scene_name"), py::arg("label_volume"), py::arg("dicom_seg"),
          py::arg("report"), py::arg("draco"));
}

}  // namespace scansurf::python
