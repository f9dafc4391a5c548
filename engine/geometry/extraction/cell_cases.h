// scansurf: tetrahedral classification of a label volume into compact per-cell case data,
// the contract between the GPU classification pass and CPU assembly.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cell_case.h"  // shaders/shared
#include "scansurf/label_volume.h"

namespace scansurf {

using CellCase = shared::CellCase;

// Corner c of a cell as (dx, dy, dz) offsets.
inline constexpr std::array<std::array<int, 3>, 8> kCellCorners = {
    {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}}};

// The four corners of each of the six tetrahedra (Freudenthal): 0, then one axis step after
// another in the order of a permutation of (x, y, z), ending at 7. Same order as classify.comp.
inline constexpr std::array<std::array<int, 4>, 6> kCellTets = {{
    {0, 1, 3, 7},  // x y z
    {0, 1, 5, 7},  // x z y
    {0, 2, 3, 7},  // y x z
    {0, 2, 6, 7},  // y z x
    {0, 4, 5, 7},  // z x y
    {0, 4, 6, 7},  // z y x
}};

// The restricted-growth partition code of four labels (see shaders/shared/cell_case.h).
std::uint32_t tetPartitionCode(Label l0, Label l1, Label l2, Label l3);

inline Label cellCornerLabel(const CellCase& c, int corner) {
  return static_cast<Label>((c.labels[corner / 2] >> (16 * (corner % 2))) & 0xFFFFu);
}
inline std::uint32_t tetCode(const CellCase& c, int tet) {
  return (c.tetCodes >> (SCANSURF_TET_CODE_BITS * tet)) & ((1u << SCANSURF_TET_CODE_BITS) - 1u);
}

// Number of cells of a grid: (nx-1)(ny-1)(nz-1).
std::uint64_t cellCount(const Grid& grid);

// The case record of cell (i, j, k); tetCodes == 0 when the cell holds no surface.
CellCase classifyCell(const LabelVolume& volume, int i, int j, int k);

// CPU reference of the GPU classification: the records of every cell holding a surface,
// sorted by cell index.
std::vector<CellCase> classifyCellsReference(const LabelVolume& volume);

}  // namespace scansurf
