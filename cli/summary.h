// scansurf CLI: what a run tells the user on stdout (the JSON report is the library's,
// scansurf/report.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scansurf/engine.h"
#include "scansurf/report.h"

namespace scansurf::cli {

// The run's results as the summary and the report see them.
struct RunFacts {
  std::string input;
  const ContourSet* contours = nullptr;
  const BuildResult* built = nullptr;
  SurfaceConvention convention = SurfaceConvention::Enclosing;
  std::vector<MeshStats> stats;  // per feature
  std::vector<StageTime> timings;
  VolumeUnit volumeUnit;  // of the volumes printed (empty name: the input's unit cubed)
};

const char* conventionName(SurfaceConvention c);

// --list-overlaps: every pair sharing voxels, its shared volume, depth and verdict, and the
// surface layers that gives. depthLimit: the tolerance's depth on the run's grid.
void printOverlapList(const ContourSet& set, const OverlapReport& report, double depthLimit);

// Prints the grid, nesting order, a line per feature and the stage times, then what was written.
void printSummary(const RunFacts& facts, const std::vector<std::filesystem::path>& written, const std::string& outDir);

}  // namespace scansurf::cli
