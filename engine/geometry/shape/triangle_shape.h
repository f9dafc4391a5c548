// scansurf: what runs between relaxation and volume restoration to shape the triangles (issue
// 28; docs/method.md, "Triangle shape"): crowded voxel centres snapped (snapping.h), the quads'
// diagonals chosen (quad_diagonals.h), the cubes' fans re-triangulated (cube_fans.h).
#pragma once

#include <vector>

#include "geometry/shape/cube_fans.h"
#include "scansurf/grid.h"
#include "scansurf/smoothing.h"
#include "scansurf/surfaces.h"

namespace scansurf {

struct ShapedTriangles {
  TriangleShapeReport report;  // all three steps, timed
  CubeDisks disks;             // for restoreVolumes, which must keep them unfolded
};

// The three steps in order on the relaxed mesh (keys intact); onSheet follows the vertices.
// cubeFans false: the third is left out (the tests of the first two alone). Deterministic for any thread count (0 = all).
ShapedTriangles shapeTriangles(MultiLabelMesh& mesh, const Grid& grid, double snapFraction, std::vector<bool>& onSheet,
                               bool cubeFans = true, int threads = 0);

}  // namespace scansurf
