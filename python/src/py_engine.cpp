// scansurf Python: devices, engines and build() with options as keywords, starting from what
// the command-line tool uses (BuildOptions::recommended).
#include <pybind11/stl.h>

#include <algorithm>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <type_traits>

#include "py_errors.h"
#include "py_types.h"

namespace scansurf::python {
namespace py = pybind11;
namespace {

template <typename T>
T as(const py::handle& value, const std::string& key, const char* what) {
  if constexpr (!std::is_same_v<T, bool>)  // True is no number of iterations, nor "interpolation off"
    if (PyBool_Check(value.ptr())) raiseInvalidArgument("option " + key + ": expected " + what + ", got bool");
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    raiseInvalidArgument("option " + key + ": expected " + what + ", got " + py::str(py::type::of(value)).cast<std::string>());
  }
}

// "auto", "off" or a whole number of layers per gap.
int interpolationFactor(const py::handle& v) {
  if (py::isinstance<py::str>(v)) {
    const auto text = v.cast<std::string>();
    if (text == "auto") return InterpolationOptions::kAuto;
    if (text == "off") return 1;
    raiseInvalidArgument("option interpolate: '" + text + "' is not \"auto\", \"off\" or a number of layers per gap");
  }
  const int n = as<int>(v, "interpolate", "\"auto\", \"off\" or an int");
  // 0 is the library's kAuto: as a number of layers it would silently mean "auto".
  if (n < 1 || n > InterpolationOptions::kMaxFactor)
    raiseInvalidArgument("option interpolate: " + std::to_string(n) + " is not \"auto\", \"off\" or 1 to " +
                         std::to_string(InterpolationOptions::kMaxFactor));
  return n;
}

// "auto", "off", a depth, or (depth, percent).
OverlapTolerance overlapTolerance(const py::handle& v) {
  OverlapTolerance t;
  if (py::isinstance<py::str>(v)) {
    const auto text = v.cast<std::string>();
    if (text == "off") t.enabled = false;
    if (text != "auto" && text != "off") raiseInvalidArgument("option overlap_tolerance: '" + text + "' is not auto or off");
    return t;
  }
  if (py::isinstance<py::tuple>(v) || py::isinstance<py::list>(v)) {
    const auto pair = as<std::pair<double, double>>(v, "overlap_tolerance", "(depth, percent)");
    t.depth = pair.first, t.percent = pair.second;
    if (!(t.depth > 0))
      raiseInvalidArgument("option overlap_tolerance: the depth must be a positive length (got " +
                           py::str(v).cast<std::string>() + ")");
    return t;
  }
  t.depth = as<double>(v, "overlap_tolerance", "\"auto\", \"off\", a depth or (depth, percent)");
  // A depth of 0 is the library's "automatic": as a length it would silently mean "auto".
  if (!(t.depth > 0))
    raiseInvalidArgument("option overlap_tolerance: the depth must be a positive length, or \"auto\" (got " +
                         py::str(v).cast<std::string>() + ")");
  return t;
}

template <typename E>
E choice(const py::handle& v, const std::string& key, std::initializer_list<std::pair<const char*, E>> names) {
  const auto text = as<std::string>(v, key, "a str");
  std::string known;
  for (const auto& [name, value] : names) {
    if (text == name) return value;
    known += (known.empty() ? "" : ", ") + std::string(name);
  }
  raiseInvalidArgument("option " + key + ": '" + text + "' is not one of " + known);
}

using Setter = std::function<void(BuildOptions&, const py::handle&)>;

// Every keyword of build(), named as the command-line flags are (without "--", "-" as "_").
const std::map<std::string, Setter>& setters() {
  static const std::map<std::string, Setter> table{
      {"voxel_size", [](BuildOptions& o, const py::handle& v) { o.grid.voxelSize = as<double>(v, "voxel_size", "a number"); }},
      {"grid",
       [](BuildOptions& o, const py::handle& v) {
         const auto n = as<std::pair<int, int>>(v, "grid", "(nx, ny)");
         o.grid.nx = n.first, o.grid.ny = n.second;
       }},
      {"convention",
       [](BuildOptions& o, const py::handle& v) {
         o.convention = choice<SurfaceConvention>(
             v, "convention", {{"enclosing", SurfaceConvention::Enclosing}, {"partition", SurfaceConvention::Partition}});
       }},
      {"overlaps",
       [](BuildOptions& o, const py::handle& v) {
         o.overlaps =
             choice<OverlapMode>(v, "overlaps", {{"layers", OverlapMode::Layers}, {"partition", OverlapMode::Partition}});
       }},
      {"overlap_tolerance", [](BuildOptions& o, const py::handle& v) { o.overlapTolerance = overlapTolerance(v); }},
      {"interpolate", [](BuildOptions& o, const py::handle& v) { o.interpolation.factor = interpolationFactor(v); }},
      {"caps",
       [](BuildOptions& o, const py::handle& v) {
         o.interpolation.caps = choice<CapShape>(v, "caps", {{"round", CapShape::Round}, {"flat", CapShape::Flat}});
       }},
      {"smooth", [](BuildOptions& o, const py::handle& v) { o.smoothing.enabled = as<bool>(v, "smooth", "a bool"); }},
      {"smooth_iterations",
       [](BuildOptions& o, const py::handle& v) { o.smoothing.iterations = as<int>(v, "smooth_iterations", "an int"); }},
      {"smooth_strength",
       [](BuildOptions& o, const py::handle& v) { o.smoothing.strength = as<double>(v, "smooth_strength", "a number"); }},
      {"contour_fit",
       [](BuildOptions& o, const py::handle& v) { o.smoothing.contourFit = as<bool>(v, "contour_fit", "a bool"); }},
      {"junction_smoothing",
       [](BuildOptions& o, const py::handle& v) { o.smoothing.junctions = as<bool>(v, "junction_smoothing", "a bool"); }},
      {"keep_volume",
       [](BuildOptions& o, const py::handle& v) { o.smoothing.keepVolumes = as<bool>(v, "keep_volume", "a bool"); }},
      {"min_angle", [](BuildOptions& o, const py::handle& v) { o.smoothing.minAngle = as<double>(v, "min_angle", "a number"); }},
      {"snap", [](BuildOptions& o, const py::handle& v) { o.smoothing.snap = as<double>(v, "snap", "a number"); }},
      {"simplify", [](BuildOptions& o, const py::handle& v) { o.simplification.enabled = as<bool>(v, "simplify", "a bool"); }},
      {"simplify_tolerance",
       [](BuildOptions& o, const py::handle& v) {
         o.simplification.tolerance = as<double>(v, "simplify_tolerance", "a number");
       }},
      {"simplify_edge_length",
       [](BuildOptions& o, const py::handle& v) {
         o.simplification.edgeLength = as<double>(v, "simplify_edge_length", "a number");
       }},
      {"simplify_min_angle",
       [](BuildOptions& o, const py::handle& v) { o.simplification.minAngle = as<double>(v, "simplify_min_angle", "a number"); }},
      {"remesh", [](BuildOptions& o, const py::handle& v) { o.remeshing.enabled = as<bool>(v, "remesh", "a bool"); }},
      {"edge_length",
       [](BuildOptions& o, const py::handle& v) { o.remeshing.edgeLength = as<double>(v, "edge_length", "a number"); }},
      {"curvature_sizing",
       [](BuildOptions& o, const py::handle& v) { o.remeshing.curvatureSizing = as<bool>(v, "curvature_sizing", "a bool"); }},
      {"threads",
       [](BuildOptions& o, const py::handle& v) {
         o.threads = as<int>(v, "threads", "an int");
         // As the command line: more threads than cores only cost memory and switches (the
         // results do not depend on the count); build() refuses a count out of range.
         const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
         if (o.threads >= 0 && o.threads <= BuildOptions::kMostThreads) o.threads = std::min(o.threads, cores);
       }},
      {"max_memory",
       [](BuildOptions& o, const py::handle& v) { o.memoryLimit = as<std::uint64_t>(v, "max_memory", "a number of bytes"); }},
  };
  return table;
}

// The options that are not the build's: the report's volume unit.
constexpr const char* kVolumeUnit = "volume_unit";

// The recommended options with the given keywords applied; None leaves a default.
// `volumeUnit` receives the volume_unit keyword's choice, checked by name.
BuildOptions optionsFrom(const py::dict& keywords, std::string* volumeUnit = nullptr) {
  BuildOptions options = BuildOptions::recommended();
  for (const auto& [key, value] : keywords) {
    const auto name = key.cast<std::string>();
    if (name == kVolumeUnit) {
      if (value.is_none()) continue;
      const std::string choice = as<std::string>(value, kVolumeUnit, "a str");
      if (auto known = volumeUnitFor(choice, "mm"); !known) raiseInvalidArgument("volume_unit: " + known.error().message);
      if (volumeUnit) *volumeUnit = choice;
      continue;
    }
    const auto setter = setters().find(name);
    if (setter == setters().end()) {
      std::string known;
      for (const auto& [k, s] : setters()) known += (known.empty() ? "" : ", ") + k;
      known += std::string(", ") + kVolumeUnit;
      raiseInvalidArgument("build() got an unknown option '" + name + "'; the options are " + known);
    }
    if (!value.is_none()) setter->second(options, value);
  }
  return options;
}

std::shared_ptr<PyResult> build(PyEngine& engine, std::shared_ptr<PyContours> contours, const py::dict& keywords) {
  auto result = std::make_shared<PyResult>();
  std::string volumeUnit = "input";
  result->options = optionsFrom(keywords, &volumeUnit);
  result->contours = std::move(contours);
  result->volumeUnit = valueOrRaise(volumeUnitFor(volumeUnit, result->contours->set.units));
  result->started = utcTimestamp();
  result->validation = engine.validation;
  std::uint64_t messages = 0;  // validation messages during this build (the engine counts since it began)
  Result<BuildResult> built = [&] {
    py::gil_scoped_release unlocked;
    const std::lock_guard<std::mutex> one(engine.mutex);
    const std::uint64_t before = engine.engine.validationMessageCount();
    Result<BuildResult> r = engine.engine.build(result->contours->set, result->options);
    messages = engine.engine.validationMessageCount() - before;
    return r;
  }();
  result->built = valueOrRaise(std::move(built));
  result->device = engine.engine.device();
  result->surfaces.resize(result->built.surfaces.features.size());
  if (messages > 0) raise({Errc::Vulkan, std::to_string(messages) + " Vulkan validation message(s) during this build"});
  return result;
}

py::dict deviceDict(const DeviceInfo& d) {
  py::dict out;
  out["name"] = d.name, out["type"] = d.type, out["driver"] = d.driver, out["borrowed"] = d.borrowed;
  out["memory_bytes"] = d.deviceMemory;
  return out;
}

py::list devices() {
  py::list out;
  for (const DeviceListing& d : valueOrRaise(listDevices())) {
    py::dict entry;
    entry["index"] = d.index, entry["name"] = d.name, entry["type"] = d.type;
    entry["usable"] = d.unusable.empty(), entry["unusable_because"] = d.unusable, entry["default"] = d.best;
    out.append(entry);
  }
  return out;
}

std::shared_ptr<PyEngine> makeEngine(const std::string& device, bool validation) {
  EngineOptions options;
  options.device = device;
  options.validation = validation;
  Result<Engine> engine = [&] {
    py::gil_scoped_release unlocked;
    return Engine::create(options);
  }();
  return std::make_shared<PyEngine>(valueOrRaise(std::move(engine)), validation);
}

}  // namespace

void registerEngine(py::module_& m) {
  py::class_<PyEngine, std::shared_ptr<PyEngine>>(m, "Engine",
                                                  "One Vulkan device; build() on it any number of times (scansurf.build "
                                                  "keeps one per device for you).")
      .def(py::init(&makeEngine), py::arg("device") = "", py::arg("validation") = false)
      .def_property_readonly("device", [](const PyEngine& e) { return deviceDict(e.engine.device()); })
      .def_property_readonly("validation", [](const PyEngine& e) { return e.validation; })
      .def_property_readonly("validation_messages", [](const PyEngine& e) { return e.engine.validationMessageCount(); });
  m.def("_build", &build, py::arg("engine"), py::arg("contours"), py::arg("options"));
  m.def("devices", &devices, "Every Vulkan device: index, name, type, whether scansurf can use it, and the default.");
  // Converts the options as build() would, without building: unknown names and wrong types raise.
  m.def(
      "_check_options", [](const py::dict& keywords) { optionsFrom(keywords); }, py::arg("options"));
  m.def("_option_names", [] {
    std::vector<std::string> names;
    for (const auto& [k, s] : setters()) names.push_back(k);
    names.push_back(kVolumeUnit);
    return names;
  });
}

}  // namespace scansurf::python
