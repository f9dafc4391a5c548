// scansurf: each separating-surface vertex's lattice edge as the keys of its two corners, and a
// voxel centre's key and indices back and forth (snapping.cpp, quad_diagonals.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/extraction/assembly.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// The key of voxel centre (i, j, k): 12 times its indices, packed as MultiLabelMesh::keys.
inline std::uint64_t cornerKey(const int corner[3]) {
  return packVertexKey(12 * static_cast<std::uint64_t>(corner[0]), 12 * static_cast<std::uint64_t>(corner[1]),
                       12 * static_cast<std::uint64_t>(corner[2]));
}

// The indices of the voxel centre whose key this is.
inline std::array<int, 3> cornerOf(std::uint64_t key) {
  return {static_cast<int>((key & kKeyMask) / 12), static_cast<int>(((key >> kKeyBits) & kKeyMask) / 12),
          static_cast<int>((key >> (2 * kKeyBits)) / 12)};
}

// A vertex's lattice edge: its corners' keys, a before b along the Freudenthal chain; b = 0 for
// a vertex off the lattice edges (a face or tetrahedron barycentre, or a voxel centre).
struct EdgeCorners {
  std::uint64_t a = 0, b = 0;
};

// Per vertex of the mesh (mesh.keys), its edge's corners. Parallel on `threads` (0 = all).
std::vector<EdgeCorners> edgeCornersOf(const MultiLabelMesh& mesh, int threads);

}  // namespace scansurf
