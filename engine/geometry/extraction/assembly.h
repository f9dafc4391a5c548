// scansurf: CPU assembly of the separating-surface mesh from per-cell case records.
#pragma once

#include <cstdint>
#include <span>

#include "geometry/extraction/cell_cases.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// Vertex positions are exact integers in units of 1/12 cell (edge midpoints, face centroids
// and tetrahedron centroids all land on that lattice); a vertex's identity is its packed key.
inline constexpr int kKeyBits = 21;
inline constexpr std::uint64_t kKeyMask = (std::uint64_t{1} << kKeyBits) - 1;
inline std::uint64_t packVertexKey(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  return x | (y << kKeyBits) | (z << (2 * kKeyBits));
}

// Builds the multi-label mesh (paper §3.5) of the records of one grid.
// casesSortedByCell: the records of classifyCellsReference or the GPU pass, sorted by cell,
// each tet code a valid partition code consistent with the record's labels (records that
// break this yield triangles whose label pair is not {a < b}). Grid axes must hold fewer than
// 2^21 / 12 voxels. threads: 0 = defaultThreadCount().
// Returns vertices in key order (mesh.keys) (z, then y, then x in twelfths), triangles in cell order and,
// within a cell, in tetrahedron and case-table order: the same for any thread count.
// Positions in input units; every triangle wound so its normal points from labels[2t]'s
// region into labels[2t+1]'s.
MultiLabelMesh assembleMesh(const Grid& grid, std::span<const CellCase> casesSortedByCell, int threads = 0);

}  // namespace scansurf
