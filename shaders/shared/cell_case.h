// Shared by GLSL (classify.comp) and C++ (engine.h, engine/geometry/extraction/cell_cases.h): the
// compact per-cell case record the tetrahedral classification emits for every cell that
// holds a separating surface.
//
// A cell is the cube between eight neighbouring voxel centres; cell (i, j, k) has corner c
// (bit 0 = +x, bit 1 = +y, bit 2 = +z) at voxel (i + (c&1), j + ((c>>1)&1), k + (c>>2)).
// It splits into six tetrahedra (Freudenthal/Kuhn), tetrahedron t walking from corner 0 to
// corner 7 along the axes in the order of permutation t, so neighbouring cells agree on
// every shared face.
//
// tetCodes holds 5 bits per tetrahedron (t at bit 5*t): the partition of its four corner
// labels l0..l3 (in kCellTets order) as r1 | r2 << 1 | r3 << 3, where r_i is the smallest
// j <= i with l_j == l_i (so r1 is 0..1, r2 0..2, r3 0..3). 0 means one label: no surface.
#ifndef SCANSURF_SHARED_CELL_CASE_H
#define SCANSURF_SHARED_CELL_CASE_H

#define SCANSURF_TETS_PER_CELL 6
#define SCANSURF_TET_CODE_BITS 5

#ifdef __cplusplus
#include <cstdint>
#define SCANSURF_UINT std::uint32_t
namespace scansurf {
#else
#define SCANSURF_UINT uint
#endif

struct CellCase {
  SCANSURF_UINT cell;       // i + (nx-1) * (j + (ny-1) * k), over the whole volume
  SCANSURF_UINT tetCodes;   // 6 x 5 bits
  SCANSURF_UINT labels[4];  // the 8 corner labels, 16 bits each: corner c in labels[c/2] bits 16*(c%2)
};

#ifdef __cplusplus
static_assert(sizeof(CellCase) == 24, "CellCase layout must match the GLSL std430 struct");
namespace shared {
using CellCase = ::scansurf::CellCase;
}
}  // namespace scansurf
#endif
#undef SCANSURF_UINT

#endif
