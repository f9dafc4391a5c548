#include "io/report_json.h"

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"

namespace scansurf {

Result<void> writeReportJson(const std::filesystem::path& path, const RunReport& report) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["format"] = "scansurf-report";
  j["version"] = 1;
  j["input"] = report.input;
  j["units"] = report.units;
  ordered_json params = ordered_json::object();
  for (const auto& [name, value] : report.parameters) std::visit([&](const auto& v) { params[name] = v; }, value);
  j["parameters"] = params;
  j["device"] = {{"name", report.deviceName}, {"type", report.deviceType}, {"driver", report.driver}};
  const Grid& g = report.grid;
  j["grid"] = {{"size", {g.nx, g.ny, g.nz}},
               {"origin", {g.originX, g.originY, g.layerZ.empty() ? 0.0 : g.layerZ.front()}},
               {"spacing_xy", {g.spacingX, g.spacingY}},
               {"layer_z", g.layerZ}};
  j["nesting"] = {{"order", report.nestingOrder}, {"from_input", report.userOrder}};
  j["multilabel_mesh"] = {{"vertices", report.meshVertices}, {"triangles", report.meshTriangles}};
  ordered_json features = ordered_json::array();
  for (const ReportFeature& f : report.features) {
    const MeshStats& s = f.stats;
    features.push_back({{"name", f.name},
                        {"label", f.label},
                        {"color", {f.color[0], f.color[1], f.color[2]}},
                        {"triangles", s.triangles},
                        {"vertices", s.vertices},
                        {"area", s.area},
                        {"volume", s.volume},
                        {"components", s.components},
                        {"genus", s.genus},
                        {"closed", s.closed},
                        {"manifold", s.manifold},
                        {"oriented", s.oriented},
                        {"files", f.files}});
  }
  j["features"] = features;
  ordered_json timings = ordered_json::array();
  double total = 0;
  for (const auto& [stage, seconds] : report.timings) {
    timings.push_back({{"stage", stage}, {"seconds", seconds}});
    total += seconds;
  }
  j["timings"] = timings;
  j["total_seconds"] = total;
  j["warnings"] = report.warnings;
  j["outputs"] = report.outputs;

  const std::string text = j.dump(2) + "\n";
  return writeFileAtomically(path, text.data(), text.size());
}

}  // namespace scansurf
