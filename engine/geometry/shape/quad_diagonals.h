// scansurf: each tetrahedron's quadrilateral of surface split along its better diagonal (issue
// 28): assembly splits a (2+2) tetrahedron's quad along a fixed diagonal; once smoothing has moved
// its corners, the other diagonal often makes two well-shaped triangles out of two slivers.
#pragma once

#include <cstddef>

#include "scansurf/surfaces.h"

namespace scansurf {

// Every two consecutive triangles that share an edge joining points of two opposite lattice edges
// of one tetrahedron (the quad of a 2+2 tetrahedron, as assembly emits it; needs mesh.keys) is
// split along the other
// diagonal instead where that raises the pair's smallest angle and both new triangles face
// the way the pair did. Both triangulations lie in that tetrahedron with the same edges on its
// faces, so the surfaces still never cross (quad_diagonals.cpp). Positions, labels and keys are
// unchanged. Deterministic for any thread count (0 = all). Returns the number of quads flipped.
std::size_t chooseQuadDiagonals(MultiLabelMesh& mesh, int threads = 0);

}  // namespace scansurf
