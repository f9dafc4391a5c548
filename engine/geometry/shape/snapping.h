// scansurf: smoothed surface vertices that crowd a lattice point merge into it, after
// Raman & Wenger, "Quality isosurface mesh generation using an extended marching cubes lookup
// table" (EuroVis 2008): the slivers of the separating surfaces are triangles with two or three
// vertices close to one voxel centre, and moving those vertices onto the centre removes them.
#pragma once

#include <vector>

#include "scansurf/grid.h"
#include "scansurf/smoothing.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// Every voxel centre p that a vertex on one of p's 14 lattice edges lies within `fraction` of
// that edge's length from, whose star carries one label pair (no junction near p) and whose
// surface there is one disk (after the snaps of its neighbours, the more crowded first): the
// vertices on p's edges that no neighbour took merge into one vertex at p. Triangles with two
// of them vanish; the others keep their tetrahedron, orientation and face curves, so the
// surfaces still never cross (snapping.cpp).
// mesh.keys stays sorted (p's key is 12 p); onSheet (SmoothingReport) follows the vertices,
// false at snapped points. Deterministic for any thread count (0 = all). fraction 0: nothing.
// The report's quadsFlipped and seconds are chooseQuadDiagonals' and the caller's to fill.
TriangleShapeReport snapToLattice(MultiLabelMesh& mesh, const Grid& grid, double fraction, std::vector<bool>& onSheet,
                                  int threads = 0);

// The fraction snapping uses on this grid: `fraction` where the contour planes lie at least two
// pixels apart, less in proportion where they lie closer (their median gap). Snapping moves a
// vertex by up to the fraction of its edge, the same share of a pixel at any slice spacing, while
// the surface's own error shrinks with the spacing: at 1 mm pixels and 1 mm slices the full
// fraction costs the sphere 18 % of its mean distance, half of it 9 % (docs/method.md).
// contourLayers: contourLayers()'s flags; with fewer than two, the median gap of all layers.
double snapFractionFor(const Grid& grid, const std::vector<bool>& contourLayers, double fraction);

// Another layer's report added in (surface_layers.cpp).
void accumulate(TriangleShapeReport& into, const TriangleShapeReport& layer);

}  // namespace scansurf
