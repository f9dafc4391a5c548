// scansurf: constrained smoothing of the multi-label separating-surface mesh (paper §3.5).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/smoothing.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// What the smoother did, by vertex role.
struct SmoothingReport {
  std::size_t sheet = 0;   // relaxed over their surface sheet
  std::size_t curve = 0;   // relaxed along a junction curve (three or more labels)
  std::size_t fixed = 0;   // junction curve meeting points and unrecognised vertices: kept
  std::size_t fitted = 0;  // placed on their contour's crossing and kept there
  int sweeps = 0;          // Jacobi sweeps run over all vertices (super-step stages)
  // Per vertex: on one label pair's sheet (relaxed, or placed on a contour or an interpolated
  // crossing), not on a junction curve: volume_restoration.h may move it.
  std::vector<bool> onSheet;
  // The keys (sorted) of the sheet vertices placed between two contour planes of their structure
  // by the blend across them (grids with no layers; geometry/smoothing/plane_blend.h): the shape
  // the contours give, which volume restoration moves only where the others cannot keep a volume.
  std::vector<std::uint64_t> betweenPlanes;
};

// Smooths mesh.positions in place; triangles, labels and keys are unchanged. Requires
// mesh.keys (assembleMesh) and the grid the mesh was assembled on; contours (the set scan
// converted onto that grid, or null) enable contour fitting. Every vertex stays strictly
// inside the lattice simplex it was the barycentre of, so the surfaces never cross (see
// smoothing.cpp). Deterministic for any thread count (0 = all). With a clearance per voxel
// of the grid (interpolated volumes, geometry/interpolation/interpolated_volume.h), every vertex on a grid
// edge that no contour fixes goes where the interpolated labels change along that edge and
// stays there, like a contour-fitted one (needs options.contourFit); the others relax.
// Without one (no layers), such a vertex between two contour planes, or between a structure's
// end plane and the next layer, goes where the structure's blended fields, or its round cap,
// cross its edge (geometry/smoothing/plane_blend.h) and stays there.
// With `medial`, the interface vertices of incidental pairs on contour planes go to the pair's
// medial line instead (geometry/overlaps/overlap_split.h).
class MedialCrossings;
SmoothingReport smoothMesh(MultiLabelMesh& mesh, const Grid& grid, const ContourSet* contours, const SmoothingOptions& options,
                           int threads = 0, std::span<const std::uint16_t> clearance = {},
                           const MedialCrossings* medial = nullptr);

}  // namespace scansurf
