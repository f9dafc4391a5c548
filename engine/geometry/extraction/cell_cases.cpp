// Tetrahedral classification of a label volume (Nielson & Franke, "Computing the separating
// surface for segmented data", IEEE Visualization 1997): each cell's six Freudenthal
// tetrahedra are reduced to the partition of their corner labels. CPU reference of
// classify.comp; both must emit identical CellCase records.
#include "geometry/extraction/cell_cases.h"

#include "core/parallel.h"

namespace scansurf {

std::uint32_t tetPartitionCode(Label l0, Label l1, Label l2, Label l3) {
  // r_i: the index of the first corner carrying corner i's label (r_i == i for a new label).
  const std::uint32_t r1 = l1 == l0 ? 0u : 1u;
  const std::uint32_t r2 = l2 == l0 ? 0u : (l2 == l1 ? r1 : 2u);
  const std::uint32_t r3 = l3 == l0 ? 0u : (l3 == l1 ? r1 : (l3 == l2 ? r2 : 3u));
  return r1 | (r2 << 1) | (r3 << 3);
}

std::uint64_t cellCount(const Grid& grid) {
  if (grid.nx < 2 || grid.ny < 2 || grid.nz < 2) return 0;
  return static_cast<std::uint64_t>(grid.nx - 1) * static_cast<std::uint64_t>(grid.ny - 1) *
         static_cast<std::uint64_t>(grid.nz - 1);
}

CellCase classifyCell(const LabelVolume& volume, int i, int j, int k) {
  const Grid& g = volume.grid;
  CellCase out{};
  out.cell = static_cast<std::uint32_t>(
      static_cast<std::uint64_t>(i) +
      static_cast<std::uint64_t>(g.nx - 1) *
          (static_cast<std::uint64_t>(j) + static_cast<std::uint64_t>(g.ny - 1) * static_cast<std::uint64_t>(k)));
  std::array<Label, 8> corner{};
  for (int c = 0; c < 8; ++c) {
    corner[c] = volume.at(i + kCellCorners[c][0], j + kCellCorners[c][1], k + kCellCorners[c][2]);
    out.labels[c / 2] |= static_cast<std::uint32_t>(corner[c]) << (16 * (c % 2));
  }
  for (int t = 0; t < SCANSURF_TETS_PER_CELL; ++t) {
    const auto& tet = kCellTets[t];
    const std::uint32_t code = tetPartitionCode(corner[tet[0]], corner[tet[1]], corner[tet[2]], corner[tet[3]]);
    out.tetCodes |= code << (SCANSURF_TET_CODE_BITS * t);
  }
  return out;
}

std::vector<CellCase> classifyCellsReference(const LabelVolume& volume) {
  const Grid& g = volume.grid;
  if (cellCount(g) == 0) return {};
  const std::size_t layers = static_cast<std::size_t>(g.nz - 1);
  const int chunks = chunkCount(layers, 0);
  std::vector<std::vector<CellCase>> perChunk(static_cast<std::size_t>(chunks));
  // Chunks are contiguous ranges of z, so concatenating them in chunk order sorts by cell.
  parallelChunks(layers, chunks, [&](int chunk, std::size_t begin, std::size_t end) {
    std::vector<CellCase>& out = perChunk[static_cast<std::size_t>(chunk)];
    for (std::size_t k = begin; k < end; ++k) {
      for (int j = 0; j + 1 < g.ny; ++j) {
        for (int i = 0; i + 1 < g.nx; ++i) {
          const CellCase c = classifyCell(volume, i, j, static_cast<int>(k));
          if (c.tetCodes != 0) out.push_back(c);
        }
      }
    }
  });
  std::size_t total = 0;
  for (const auto& v : perChunk) total += v.size();
  std::vector<CellCase> result;
  result.reserve(total);
  for (auto& v : perChunk) {
    result.insert(result.end(), v.begin(), v.end());
    std::vector<CellCase>().swap(v);
  }
  return result;
}

}  // namespace scansurf
