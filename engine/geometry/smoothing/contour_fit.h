// scansurf: contour-faithful vertices. On a contour plane, a separating-surface vertex that sits
// on an in-plane grid edge between two labels is moved to where the original contour crosses
// that edge, so the surface's cross-section there follows the contour, not the pixel staircase.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/label_volume.h"

namespace scansurf {

// The voxel corners (i, j, k) of the lattice simplex whose barycentre is the vertex with this
// packed key (geometry/extraction/assembly.h): 2 for an edge midpoint, 3 for a face centroid, 4 for a
// tetrahedron centroid, in chain order (each corner one or more axis steps past the previous);
// count 0 for a key that is no such barycentre.
struct Carrier {
  int count = 0;
  int corners[4][3] = {};
};
Carrier carrierOfKey(std::uint64_t key);

// The runs of vertices with one z key (keys: MultiLabelMesh::keys, sorted by z first): z is in
// twelfths of a layer, 12 k on layer k, 12 k + 6 on the grid edges from layer k to k + 1.
struct ZKeyRun {
  std::uint64_t z;
  std::size_t begin, end;
};
std::vector<ZKeyRun> runsOfZKey(std::span<const std::uint64_t> keys);

// For each vertex (keys: MultiLabelMesh::keys, sorted), the parameter t in [0, 1] from the
// first corner of its carrier edge to the second where an original contour of one of the
// vertex's two labels (vertexLabels: 2 per vertex; background has no contours) crosses that
// edge, choosing the crossing nearest the edge midpoint; -1 for vertices not on an in-plane
// edge of a layer, or whose edge no such contour crosses. Slices belong to the layer within
// their z (Grid::layerOfPlane). Deterministic for any thread count (0 = all).
std::vector<double> fitContourCrossings(const Grid& grid, const ContourSet& contours, std::span<const std::uint64_t> keys,
                                        std::span<const Label> vertexLabels, int threads);

// The pixel-lattice cells (ci | cj << 32, within nx x ny) whose closed square [ci, ci+1] x
// [cj, cj+1] the segment (u0, v0)-(u1, v1) touches, in pixel units: the cells whose lower and
// left lattice edges it can cross. O(length) cells, column by column; appended to `cells`.
void appendTouchedCells(double u0, double v0, double u1, double v1, int nx, int ny, std::vector<std::uint64_t>& cells);

}  // namespace scansurf
