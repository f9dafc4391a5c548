// scansurf: verified simplification of the smoothed multi-label surface network: quadric-error
// edge collapses (Garland & Heckbert 1997, geometry/simplification/edge_collapse.h) in patches with locked borders.
#pragma once

#include <vector>

#include "scansurf/grid.h"
#include "scansurf/simplification.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// Simplifies `mesh` in place. The mesh is cut into patches: one label pair's triangles in one
// tile of kTilePixels x kTilePixels pixels between two cuts along z, a cut at every contour
// layer (contourLayers[k]: a contour lies on layer k) and at least every kTierLayers layers.
// Each patch is simplified on its own; its vertices on contour planes and those it shares with
// another patch (junction curves, tile and tier cuts) stay, so the cross-sections at the contour
// planes and every junction curve are kept vertex for vertex and patches still meet where they
// met. A patch's result is kept only if it has the same border, Euler characteristic and
// components, is a manifold with every edge used once each way, adds no edge along a contour
// plane, has no degenerate triangle, turns no new triangle against the smoothed surface, and
// (exact test) crosses no triangle near it; otherwise the patch stays as smoothed. Unused
// vertices are dropped and mesh.keys is cleared. The result depends on the mesh and options
// only, never on `threads` (0: all).
inline constexpr int kTierLayers = 8;
inline constexpr int kTilePixels = 32;
SimplificationReport simplifyMesh(MultiLabelMesh& mesh, const Grid& grid, const std::vector<bool>& contourLayers,
                                  const SimplificationOptions& options, int threads = 0);

// Adds a layer's figures to the run's (Surfaces::simplification): counts summed, smallest angle
// and 5th percentile the least of the two, means weighted by triangles.
void accumulate(SimplificationReport& into, const SimplificationReport& layer);

}  // namespace scansurf
