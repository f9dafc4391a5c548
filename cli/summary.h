// scansurf CLI: what a run tells the user — the human summary on stdout and the JSON report.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "io/report_json.h"
#include "scansurf/engine.h"

namespace scansurf::cli {

// The run's results as the summary and the report see them.
struct RunFacts {
  std::string input;
  const ContourSet* contours = nullptr;
  const BuildResult* built = nullptr;
  const DeviceInfo* device = nullptr;
  SurfaceConvention convention = SurfaceConvention::Enclosing;
  std::vector<MeshStats> stats;  // per feature
  std::vector<StageTime> timings;
};

const char* conventionName(SurfaceConvention c);

// The report (per-feature statistics, parameters, device, grid, order, timings); `files` are
// each feature's output files, `outputs` every file the run writes.
RunReport makeRunReport(const RunFacts& facts,
                        std::vector<std::pair<std::string, std::variant<bool, double, std::string>>> parameters,
                        const std::vector<std::vector<std::filesystem::path>>& files,
                        const std::vector<std::filesystem::path>& outputs);

// Prints the grid, nesting order, a line per feature and the stage times, then what was written.
void printSummary(const RunFacts& facts, const std::vector<std::filesystem::path>& written, const std::string& outDir);

}  // namespace scansurf::cli
