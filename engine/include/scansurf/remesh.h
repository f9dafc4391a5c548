// scansurf: options and figures of the remeshing of the separating-surface network into
// well-shaped triangles of about one edge length (after Botsch & Kobbelt 2004).
#pragma once

#include <cstddef>

namespace scansurf {

struct RemeshOptions {
  // Off by default, in the library and the command-line tool: it is slow yet. Runs
  // after smoothing, on the whole multi-label mesh; one of 400 000 triangles or more in chunks
  // along z, on BuildOptions::threads threads, with the same output for any thread count.
  bool enabled = false;
  // Target edge length in input units; 0 = 1.15 times
  // the grid's in-plane voxel size (the smaller of its x and y spacings) or 0.33 times the
  // median gap between contour planes, whichever is longer: clinical-scale structure sets then get fewer
  // triangles than flying edges + windowed sinc on the same grid. Around
  // feature-line edges that stay shorter (a contour's close points) the target shrinks
  // gradually, so the triangles there are small rather than thin.
  double edgeLength = 0;
  // A set edgeLength must lie within these many in-plane voxels of the run's grid (refused
  // otherwise, Errc::InvalidArgument): finer grows the mesh as 1 / length^2, coarser cannot
  // collapse within the surface bound.
  static constexpr double kLeastVoxels = 0.25, kMostVoxels = 16;
  // Curvature sizing: where the surface curves so tightly that a chord of the target length
  // would stand more than 0.2 voxel inside it at its middle (radius under about 0.6 L^2 per
  // voxel: a thin bar's sides and ends, a vessel's branch), the target shrinks to the longest
  // chord that does not, down to 0.3 L, and grows back gradually around it. Off: one target
  // everywhere but around short feature-line edges.
  bool curvatureSizing = true;
  // Split / collapse / flip / relax rounds (Botsch & Kobbelt use 5 to 10; past 4 the angles
  // of analytic test shapes no longer improve).
  int iterations = 4;
};

// Triangle angles in degrees.
struct AngleFigures {
  double min = 0, p5 = 0, mean = 0;  // smallest, 5th percentile, mean of every triangle's smallest angle
};

// What remeshing did; ran = false when it did not run.
struct RemeshReport {
  bool ran = false;
  std::size_t trianglesBefore = 0, trianglesAfter = 0;
  AngleFigures anglesBefore, anglesAfter;
  double edgeLength = 0;  // the target used, input units
  // Largest distance of the remeshed surface (vertices, edge midpoints and centroids) from
  // the smoothed surface it replaced, input units.
  double maxDistance = 0;
  // How the work was split: chunks remeshed in parallel, then bands around their cuts (1 and 0:
  // the mesh was remeshed whole; with overlaps as layers, summed over the layers).
  std::size_t chunks = 1, bands = 0;
  std::size_t splits = 0, collapses = 0, flips = 0, moves = 0;  // operations applied
  std::size_t rejected = 0;                                     // operations refused by a validity check
};

}  // namespace scansurf
