// scansurf: the memory a build will need, estimated from the contours and the grid before
// anything large is allocated, to refuse clearly instead of failing in bad_alloc or an OOM kill.
#pragma once

#include <cstdint>

#include "scansurf/contours.h"
#include "scansurf/grid.h"

namespace scansurf {

struct Footprint {
  std::uint64_t labelVoxels = 0;      // voxels of the label volume (one layer of features)
  std::uint64_t surfaceVertices = 0;  // estimated vertices of the multi-label mesh
  std::uint64_t hostBytes = 0;        // estimated peak host memory of build()
  std::uint64_t deviceBytes = 0;      // device memory scan conversion and classification need at least
};

// The separating surface crosses the grid where a contour crosses pixel boundaries on its
// layer and where a feature's area changes between layers (caps included); vertices scale with
// those crossings. Calibrated on measured peaks (docs/limits.md), on the generous side: the peak counts the label volume, the
// classification records, the mesh with its smoothing state and the feature surfaces. With interpolation the surfaced volume has
// `surfacedLayers` layers instead of grid.nz: its labels count too, and the side walls gain vertices in proportion. With
// remeshing to edges of `remeshLength` (input units; 0 = no remeshing), its network and the remeshed mesh count too: at edges
// under half a voxel the mesh grows as 1 / length^2.
Footprint estimateFootprint(const ContourSet& contours, const Grid& grid, int surfacedLayers = 0, double remeshLength = 0);

}  // namespace scansurf
