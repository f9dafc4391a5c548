// scansurf: what a run is refused for before any work (see run_checks.h).
#include "run_checks.h"

#include <cmath>
#include <cstdio>

#include "core/memory.h"
#include "geometry/grid/footprint.h"

namespace scansurf {
namespace {

Unexpected badOption(const std::string& option, const std::string& allowed, double value) {
  char got[64];
  std::snprintf(got, sizeof got, "%g", value);
  return makeError(Errc::InvalidArgument, "option " + option + " must be " + allowed + " (got " + got + ")");
}

Result<void> checkOverlapTolerance(const OverlapTolerance& t) {
  if (!std::isfinite(t.depth) || t.depth < 0)
    return makeError(Errc::InvalidArgument, "overlap tolerance: the depth must be a finite length, 0 (automatic) or more (got " +
                                                std::to_string(t.depth) + ")");
  if (!std::isfinite(t.percent) || t.percent < 0 || t.percent > 100)
    return makeError(Errc::InvalidArgument,
                     "overlap tolerance: the percentage must lie in [0, 100] (got " + std::to_string(t.percent) + ")");
  return {};
}

// "950", "44 k", "3.3 M": a count for people.
std::string formatCount(std::uint64_t n) {
  if (n < 10000) return std::to_string(n);
  if (n < 10000000) return std::to_string((n + 500) / 1000) + " k";
  return std::to_string((n + 500000) / 1000000) + " M";
}

}  // namespace

// A remeshing target far off the grid's scale is refused before the run: under a quarter voxel
// the mesh grows as 1 / length^2 (1e-6 reached 3.5 GB), beyond 16 voxels every collapse is
// tried and fails against the surface bound (1e9 took 93 s for an unchanged mesh).
Result<void> checkEdgeLength(const RemeshOptions& r, const Grid& grid) {
  if (!r.enabled || r.edgeLength == 0) return {};
  const double voxel = std::min(grid.spacingX, grid.spacingY);
  if (r.edgeLength >= RemeshOptions::kLeastVoxels * voxel && r.edgeLength <= RemeshOptions::kMostVoxels * voxel) return {};
  char range[96];
  std::snprintf(range, sizeof range, "between %.3g and %.3g (%g to %g in-plane voxels of this grid)",
                RemeshOptions::kLeastVoxels * voxel, RemeshOptions::kMostVoxels * voxel, RemeshOptions::kLeastVoxels,
                RemeshOptions::kMostVoxels);
  return badOption("remeshing.edgeLength", range, r.edgeLength);
}

std::string describeGrid(const Grid& grid) {
  return std::to_string(grid.nx) + " x " + std::to_string(grid.ny) + " x " + std::to_string(grid.nz) + " voxels";
}

// One policy for bad options: refused, naming the option and what it may be; never clamped or
// replaced by a default behind the caller's back. A stage that is off has its options checked
// too: the report records them, and turning the stage on must not be what reveals them.
Result<void> checkOptions(const BuildOptions& o) {
  const SmoothingOptions& s = o.smoothing;
  if (!(s.strength > 0 && s.strength <= 1)) return badOption("smoothing.strength", "in (0, 1]", s.strength);
  if (!(s.minAngle >= 0 && s.minAngle <= 30)) return badOption("smoothing.minAngle", "in [0, 30] degrees", s.minAngle);
  if (!(s.snap >= 0 && s.snap <= 0.45)) return badOption("smoothing.snap", "in [0, 0.45] of a lattice edge", s.snap);
  if (s.iterations < 1 || s.iterations > SmoothingOptions::kMostIterations)
    return badOption("smoothing.iterations", "1 to " + std::to_string(SmoothingOptions::kMostIterations), s.iterations);
  {
    const SimplificationOptions& p = o.simplification;
    if (!(p.tolerance > 0 && p.tolerance <= SimplificationOptions::kMostTolerance))
      return badOption("simplification.tolerance", "in (0, 0.5] in-plane voxels", p.tolerance);
    if (!(p.edgeLength >= SimplificationOptions::kLeastEdge && p.edgeLength <= SimplificationOptions::kMostEdge))
      return badOption("simplification.edgeLength", "in [0.5, 8] in-plane voxels", p.edgeLength);
    if (!(p.minAngle >= 0 && p.minAngle <= 30)) return badOption("simplification.minAngle", "in [0, 30] degrees", p.minAngle);
  }
  const RemeshOptions& r = o.remeshing;
  if (!(std::isfinite(r.edgeLength) && r.edgeLength >= 0))
    return badOption("remeshing.edgeLength", "0 (automatic) or a positive length", r.edgeLength);
  if (r.iterations < 1) return badOption("remeshing.iterations", "at least 1", r.iterations);
  const int f = o.interpolation.factor;
  if (f != InterpolationOptions::kAuto && (f < 1 || f > InterpolationOptions::kMaxFactor))
    return badOption("interpolation.factor", "kAuto (0) or 1 to " + std::to_string(InterpolationOptions::kMaxFactor), f);
  if (!(o.audit.volumeTolerance > 0 && o.audit.volumeTolerance <= 1))
    return badOption("audit.volumeTolerance", "in (0, 1]", o.audit.volumeTolerance);
  if (o.threads < 0 || o.threads > BuildOptions::kMostThreads)
    return badOption("threads", "0 (all cores) to " + std::to_string(BuildOptions::kMostThreads), o.threads);
  const double tol = o.grid.sliceTolerance;
  if (!(std::isfinite(tol) && tol >= 0))
    return badOption("grid.sliceTolerance", "0 (the contours' own) or a positive length", tol);
  return checkOverlapTolerance(o.overlapTolerance);
}

// Refuses a build that would need more host memory than the limit or more device memory than
// the device has, before anything large is allocated: a clear error instead of bad_alloc or
// the kernel's OOM killer.
Result<void> checkMemoryBudget(const ContourSet& contours, const Grid& grid, int surfacedLayers, const BuildOptions& options,
                               const DeviceInfo& device, BuildResult& out) {
  const Footprint need =
      estimateFootprint(contours, grid, surfacedLayers, options.remeshing.enabled ? options.remeshing.edgeLength : 0);
  HostMemory limit{options.memoryLimit, "the limit asked for"};
  if (limit.bytes == 0) limit = availableHostMemory();
  const std::uint64_t hostBytes = need.hostBytes + options.reservedMemory;
  out.estimatedMemory = hostBytes;
  out.memoryLimit = limit.bytes;
  const std::string what = "the surfaces of " + contours.source + " on a grid of " + describeGrid(grid);
  const std::string reserved =
      options.reservedMemory > 0 ? ", and " + formatBytes(options.reservedMemory) + " beside them (a preview)" : "";
  if (limit.bytes > 0 && hostBytes > limit.bytes)
    return makeError(Errc::ResourceLimit, what + " need about " + formatBytes(hostBytes) + " of memory (label volume " +
                                              formatBytes(need.labelVoxels * sizeof(Label)) + ", about " +
                                              formatCount(need.surfaceVertices) + " surface vertices" + reserved + "); " +
                                              formatBytes(limit.bytes) + " may be used: " + limit.source);
  if (device.deviceMemory > 0 && need.deviceBytes > device.deviceMemory)
    return makeError(Errc::ResourceLimit, what + " need about " + formatBytes(need.deviceBytes) +
                                              " of device memory for one layer; the device has " +
                                              formatBytes(device.deviceMemory));
  return {};
}

}  // namespace scansurf
