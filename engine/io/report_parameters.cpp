// scansurf: the options of a run as its report records them (scansurf/report.h).
#include <cstdint>
#include <string>

#include "scansurf/engine.h"
#include "scansurf/outputs.h"
#include "scansurf/report.h"

namespace scansurf {
namespace {

ReportValue integer(std::int64_t v) { return ReportValue{v}; }

std::string gridSource(const RunSettings& s) {
  if (s.build.grid.voxelSize > 0) return "voxel size";
  if (s.build.grid.nx > 0) return "pixel counts";
  if (!s.referenceSeries.empty()) return "reference CT";
  return "default (256 pixels along the longer side)";
}

std::string interpolationName(int factor) {
  if (factor == InterpolationOptions::kAuto) return "auto";
  return factor == 1 ? "off" : std::to_string(factor);
}

}  // namespace

std::vector<std::pair<std::string, ReportValue>> runParameters(const RunSettings& s, const BuildResult& built) {
  const BuildOptions& b = s.build;
  const DracoOptions& d = s.scene.dracoOptions;
  const Grid& grid = built.volume.grid;
  return {{"convention", b.convention == SurfaceConvention::Enclosing ? "enclosing" : "partition"},
          {"overlaps", overlapModeName(b.overlaps)},
          {"overlap_tolerance", b.overlapTolerance.enabled},  // incidental overlaps split in one layer
          {"overlap_depth", incidentalDepthLimit(b.overlapTolerance, grid)},
          {"overlap_percent", b.overlapTolerance.percent},
          {"voxel_size", grid.spacingX},
          {"voxel_size_y", grid.spacingY},
          {"grid_nx", integer(grid.nx)},
          {"grid_ny", integer(grid.ny)},
          {"grid_source", gridSource(s)},
          {"threads", integer(built.threads)},
          {"interpolation", interpolationName(b.interpolation.factor)},
          {"layers_per_gap_min", integer(built.interpolation.minFactor)},
          {"layers_per_gap_max", integer(built.interpolation.maxFactor)},
          {"caps", b.interpolation.caps == CapShape::Flat ? "flat" : "round"},
          {"smoothing", b.smoothing.enabled},
          {"smoothing_iterations", integer(b.smoothing.iterations)},
          {"smoothing_strength", b.smoothing.strength},
          {"contour_fit", b.smoothing.contourFit},
          {"junction_smoothing", b.smoothing.junctions},
          {"keep_volume", b.smoothing.keepVolumes},
          {"min_angle", b.smoothing.minAngle},
          {"snap", b.smoothing.snap},
          {"simplification", b.simplification.enabled},
          {"simplify_tolerance", b.simplification.tolerance},
          {"simplify_edge_length", b.simplification.edgeLength},
          {"simplify_min_angle", b.simplification.minAngle},
          {"remeshing", b.remeshing.enabled},
          {"edge_length", built.surfaces.remeshing.ran ? built.surfaces.remeshing.edgeLength : b.remeshing.edgeLength},
          {"curvature_sizing", b.remeshing.curvatureSizing},
          {"draco", s.scene.draco},
          {"draco_bits", integer(d.quantizationBits)},  // 0: enough for draco_max_error
          {"draco_max_error", d.quantizationBits ? 0.0 : defaultQuantizationError(grid)},
          {"draco_level", integer(d.compressionLevel)},
          {"reference", s.referenceSeries.string()},
          {"validation", s.validation}};
}

}  // namespace scansurf
