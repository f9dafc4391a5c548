// scansurf: the machine-readable report of a run (--report report.json): per-feature
// statistics, the run's parameters, device and stage timings.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf {

struct ReportFeature {
  std::string name;
  int label = 0;
  Rgb color{};
  MeshStats stats;
  std::vector<std::string> files;  // outputs holding this feature's surface
};

struct RunReport {
  std::string input;
  std::string units = "mm";
  std::vector<std::pair<std::string, std::variant<bool, double, std::string>>> parameters;
  std::string deviceName, deviceType, driver;
  Grid grid;
  std::vector<std::string> nestingOrder;  // feature names, innermost first
  bool userOrder = false;
  std::size_t meshVertices = 0, meshTriangles = 0;
  std::vector<ReportFeature> features;
  std::vector<std::pair<std::string, double>> timings;  // stage, seconds
  std::vector<std::string> warnings;
  std::vector<std::string> outputs;
};

// Writes the report as JSON (format "scansurf-report", version 1): areas in units², volumes
// in units³, times in seconds. Replaced atomically. Errors: Errc::Io naming the path.
Result<void> writeReportJson(const std::filesystem::path& path, const RunReport& report);

}  // namespace scansurf
