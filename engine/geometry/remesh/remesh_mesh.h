// scansurf: isotropic remeshing of the whole multi-label separating-surface network, after
// smoothing (Botsch & Kobbelt 2004), keeping every guarantee smoothing gave.
#pragma once

#include <span>

#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/nesting.h"
#include "scansurf/remesh.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// Remeshes `mesh` in place toward triangles of edge length options.edgeLength (0: 1.15 times
// the grid's in-plane voxel size or 0.33 times the median contour-plane gap, whichever is
// longer), graded down around short feature-line edges. Labels stay with their triangles;
// junction curves (three or more labels) and the cross-sections at the contour planes (the z of contours' slices, within
// grid.planeTolerance; contours may be null: no planes) are feature lines that are only split or
// shortened along themselves, and their meeting points stay. An operation is kept only if,
// afterwards, every feature surface of both conventions (nesting.parent.size() features) is
// still a closed oriented 2-manifold of the same genus and components, no triangle crosses
// another (exact test), no triangle turned over, and the surface lies within a tenth of a
// voxel (cross-sections: a twentieth) of the smoothed one. mesh.keys is cleared. A mesh of at
// least two chunks' worth of triangles (trianglesPerChunk; 0: never) is remeshed in chunks
// along z, up to `threads` at once (0: all); the output depends on trianglesPerChunk, never on
// threads. Returns the figures; ran = false when disabled or empty.
inline constexpr std::size_t kTrianglesPerChunk = 200'000;
RemeshReport remeshMesh(MultiLabelMesh& mesh, const Grid& grid, const ContourSet* contours, const Nesting& nesting,
                        const RemeshOptions& options, int threads = 0, std::size_t trianglesPerChunk = kTrianglesPerChunk);

// Adds a layer's figures to the run's (Surfaces::remeshing): counts summed, smallest angle
// and 5th percentile the least of the two, means weighted by triangles, distance the largest.
void accumulate(RemeshReport& into, const RemeshReport& layer);

// The smallest angle of each triangle (3 indices each into xyz positions), summarized; the
// same figures for any thread count (0 = all).
AngleFigures computeAngleFigures(std::span<const float> positions, std::span<const std::uint32_t> triangles, int threads = 1);

}  // namespace scansurf
