// scansurf: the machine-readable report of a run (format "scansurf-report"): per-feature
// statistics, the run's parameters, device, grid, nesting order, stage timings and outputs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "scansurf/build_result.h"
#include "scansurf/contours.h"
#include "scansurf/device.h"
#include "scansurf/grid.h"
#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf {

struct BuildOptions;  // scansurf/engine.h
struct SceneOptions;  // scansurf/outputs.h

struct ReportFeature {
  std::string name;
  int label = 0;
  Rgb color{};
  MeshStats stats;                                       // stats.volume: the surface volume
  std::vector<std::string> files;                        // outputs holding this feature's surface
  FeatureVolumes volumes;                                // contour and labelled voxel volume, layer, mask layer
  std::vector<std::string> sharesSurfaceWith;            // features across its separating surfaces
  std::vector<std::pair<std::string, double>> overlaps;  // partly overlapping features, shared volume
  int sourceNumber = 0;                                  // Feature::sourceNumber (ROI Number, object number); 0 = none
  std::string interpretedType;                           // Feature::interpretedType (RT ROI Interpreted Type)
};

using ReportValue = std::variant<bool, std::int64_t, double, std::string>;

// A file the contours were read from, and its SHA-256 (hex; empty when it could not be read).
struct InputFile {
  std::string path;
  std::string sha256;
  std::uint64_t bytes = 0;
};

struct RunReport {
  std::string generator;  // "scansurf <version>"
  std::string input;
  std::vector<InputFile> inputFiles;       // ContourSet::files, hashed
  std::string frameOfReferenceUid;         // ContourSet::frameOfReferenceUid
  std::optional<GridReference> reference;  // the CT lattice the label volume lies on (ContourSet::reference)
  std::vector<std::string> commandLine;
  std::string started;
  std::string units = "mm";
  std::string volumeUnit = "mm^3";  // every volume below is in it
  std::vector<std::pair<std::string, ReportValue>> parameters;
  std::string deviceName, deviceType, driver;
  Grid grid;
  std::vector<std::string> nestingOrder;  // feature names, innermost first
  bool userOrder = false;
  std::size_t meshVertices = 0, meshTriangles = 0;
  std::uint64_t estimatedMemory = 0, memoryLimit = 0;  // the budget check (BuildResult)
  InterpolationSummary interpolation;
  std::vector<ReportFeature> features;
  std::string overlapMode = "layers";
  int layers = 1, maskLayers = 1;
  struct Loss {
    std::string feature, to;
    double volume = 0, percentOfContour = 0;
    bool nested = false;
  };
  std::vector<Loss> losses;  // OverlapMode::Partition only
  OverlapTolerance overlapTolerance;
  double overlapDepthLimit = 0;  // the tolerance's depth on the grid (input units)
  // Every partial overlap: its verdict and, when incidental, what each side gave up.
  struct Overlap {
    std::string a, b;
    double volume = 0, percentOfSmaller = 0;
    double depth = 0;  // valid when depthMeasured
    bool depthMeasured = false;
    int regions = 0;  // connected regions of the shared voxels
    bool incidental = false;
    double givenUpByA = 0, givenUpByB = 0;
    double givenUpPercentA = 0, givenUpPercentB = 0;  // of each one's contour volume
  };
  std::vector<Overlap> partialOverlaps;
  std::vector<std::pair<std::string, double>> timings;  // stage, seconds
  SimplificationReport simplification;                  // BuildResult::surfaces.simplification
  TriangleShapeReport triangleShape;                    // BuildResult::surfaces.triangleShape
  RemeshReport remeshing;                               // BuildResult::surfaces.remeshing
  std::vector<std::string> warnings;
  std::vector<std::string> outputs;
};

// The unit of the report's and the summary's volumes: `name` as the report states it ("cm^3";
// empty: the input's length unit cubed) and `scale`, one cubed input unit in it.
struct VolumeUnit {
  std::string name;
  double scale = 1;
};

// The unit `choice` names for volumes in `inputUnits` cubed: "input" (the input's unit cubed),
// "mm3", "cm3" (also "cc", "ml"), "um3", "nm3". Errors: Errc::InvalidArgument for another
// choice, or for a conversion from an input unit of unknown length (pixels).
Result<VolumeUnit> volumeUnitFor(const std::string& choice, const std::string& inputUnits);

// What makeReport needs beyond the run's results.
struct ReportContext {
  std::string input;                                            // the input as the user named it
  std::vector<std::pair<std::string, ReportValue>> parameters;  // the options that shaped the run
  std::vector<StageTime> timings;                               // every stage, in order
  std::vector<std::vector<std::filesystem::path>> files;        // per feature: files with its surface (may be empty)
  std::vector<std::filesystem::path> outputs;                   // every file the run writes
  std::vector<std::string> commandLine;                         // the program's arguments, when it has them
  std::string started;                                          // when the run started, ISO 8601 UTC
  VolumeUnit volumeUnit;                                        // of every volume in the report
};

// The report of a build: statistics of every feature surface (computeMeshStats), the grid,
// nesting order, device, warnings; `stats` may hold them already (one per feature), else the
// build's audit's are used, or (a result made without Engine::build) they are computed.
RunReport makeReport(const ContourSet& contours, const BuildResult& built, const DeviceInfo& device, ReportContext context,
                     std::vector<MeshStats> stats = {});

// Writes the report as JSON (format "scansurf-report", version 1): the unit of lengths, areas
// and volumes stated (length_unit, area_unit, volume_unit: areas in units², volumes in units³
// or the context's volume unit),
// times in seconds, the command line and start time when known. Staged and renamed. Errors: Errc::Io naming the path.
Result<void> writeReport(const std::filesystem::path& path, const RunReport& report);
// The time now as ISO 8601 UTC ("2026-12-01T22:07:11Z"), for ReportContext::started.
std::string utcTimestamp();

// The same JSON text, for an application that keeps the report in memory (the Python package's
// BuildResult.report).
std::string reportJson(const RunReport& report);

// The options that shaped a run, as its report records them: every default resolved to the
// value used (the grid's pixel size and counts, the threads, the remeshing length), lengths in
// the input's units. `referenceSeries` is the CT folder the contours were read with (empty:
// none); `validation` whether the Vulkan validation layers were on.
struct RunSettings {
  const BuildOptions& build;
  const SceneOptions& scene;
  std::filesystem::path referenceSeries;
  bool validation = false;
};
std::vector<std::pair<std::string, ReportValue>> runParameters(const RunSettings& settings, const BuildResult& built);

}  // namespace scansurf
