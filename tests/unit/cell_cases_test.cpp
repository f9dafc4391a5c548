#include "geometry/extraction/cell_cases.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <random>
#include <set>
#include <string>

namespace scansurf {
namespace {

// Literal reading of the contract: r_i = index of the first corner with corner i's label.
std::uint32_t expectedCode(const std::array<Label, 4>& l) {
  std::array<std::uint32_t, 4> r{};
  for (std::uint32_t i = 0; i < 4; ++i) {
    r[i] = i;
    for (std::uint32_t j = 0; j < i; ++j)
      if (l[j] == l[i]) {
        r[i] = j;
        break;
      }
  }
  return r[1] | (r[2] << 1) | (r[3] << 3);
}

TEST(TetPartitionCode, HandPicked) {
  EXPECT_EQ(tetPartitionCode(5, 5, 5, 5), 0u);
  EXPECT_EQ(tetPartitionCode(0, 1, 1, 1), 1u | (1u << 1) | (1u << 3));  // 1+3
  EXPECT_EQ(tetPartitionCode(0, 0, 0, 1), 3u << 3);                     // 3+1, lone last
  EXPECT_EQ(tetPartitionCode(4, 9, 4, 9), 1u | (0u << 1) | (1u << 3));  // 2+2
  EXPECT_EQ(tetPartitionCode(4, 4, 9, 9), 0u | (2u << 1) | (2u << 3));  // 2+2
  EXPECT_EQ(tetPartitionCode(1, 2, 3, 4), 1u | (2u << 1) | (3u << 3));  // all distinct
  EXPECT_EQ(tetPartitionCode(7, 3, 3, 0), 1u | (1u << 1) | (3u << 3));
}

TEST(TetPartitionCode, AllPatternsExactAndFifteenDistinct) {
  std::set<std::uint32_t> codes;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 4; ++c)
        for (int d = 0; d < 4; ++d) {
          const std::array<Label, 4> l = {Label(a * 7), Label(b * 7), Label(c * 7), Label(d * 7)};
          const std::uint32_t code = tetPartitionCode(l[0], l[1], l[2], l[3]);
          EXPECT_EQ(code, expectedCode(l));
          EXPECT_LT(code, 1u << SCANSURF_TET_CODE_BITS);
          EXPECT_EQ(code == 0, a == b && b == c && c == d);
          codes.insert(code);
        }
  EXPECT_EQ(codes.size(), 15u);  // Bell number B4
}

LabelVolume makeVolume(int nx, int ny, int nz) {
  LabelVolume v;
  v.grid.nx = nx;
  v.grid.ny = ny;
  v.grid.nz = nz;
  for (int k = 0; k < nz; ++k) v.grid.layerZ.push_back(k);
  v.labels.assign(v.grid.voxelCount(), 0);
  return v;
}

TEST(CellCount, Grid) {
  LabelVolume v = makeVolume(3, 4, 5);
  EXPECT_EQ(cellCount(v.grid), 2u * 3u * 4u);
  EXPECT_EQ(cellCount(makeVolume(1, 4, 5).grid), 0u);
}

TEST(ClassifyCell, UniformCellHasNoSurface) {
  LabelVolume v = makeVolume(2, 2, 2);
  std::fill(v.labels.begin(), v.labels.end(), Label{3});
  const CellCase c = classifyCell(v, 0, 0, 0);
  EXPECT_EQ(c.cell, 0u);
  EXPECT_EQ(c.tetCodes, 0u);
  for (int corner = 0; corner < 8; ++corner) EXPECT_EQ(cellCornerLabel(c, corner), 3);
  EXPECT_TRUE(classifyCellsReference(v).empty());
}

TEST(ClassifyCell, SingleCornerTouchesEveryTetOrOnlyItsOwn) {
  // Corner 0 lies on every tet: all six codes are "lone first corner" (0 | 1 | 1).
  LabelVolume v = makeVolume(2, 2, 2);
  v.labels[v.grid.index(0, 0, 0)] = 1;
  CellCase c = classifyCell(v, 0, 0, 0);
  const std::uint32_t lone0 = 1u | (1u << 1) | (1u << 3);
  for (int t = 0; t < 6; ++t) EXPECT_EQ(tetCode(c, t), lone0) << t;
  EXPECT_EQ(c.labels[0], 1u);
  EXPECT_EQ(c.labels[1] | c.labels[2] | c.labels[3], 0u);

  // Corner 1 (+x) lies on tets 0 and 1 only, as their second corner: code r1 = 1.
  v.labels.assign(8, 0);
  v.labels[v.grid.index(1, 0, 0)] = 2;
  c = classifyCell(v, 0, 0, 0);
  EXPECT_EQ(cellCornerLabel(c, 1), 2);
  EXPECT_EQ(c.labels[0], 2u << 16);
  for (int t = 0; t < 6; ++t) EXPECT_EQ(tetCode(c, t), t < 2 ? 1u : 0u) << t;
}

TEST(ClassifyCell, LabelsPackedAndCodesPerTet) {
  LabelVolume v = makeVolume(2, 2, 2);
  for (int corner = 0; corner < 8; ++corner)
    v.labels[v.grid.index(kCellCorners[corner][0], kCellCorners[corner][1], kCellCorners[corner][2])] =
        static_cast<Label>(100 + corner % 3);
  const CellCase c = classifyCell(v, 0, 0, 0);
  for (int corner = 0; corner < 8; ++corner) EXPECT_EQ(cellCornerLabel(c, corner), 100 + corner % 3);
  for (int t = 0; t < 6; ++t) {
    const auto& tet = kCellTets[t];
    EXPECT_EQ(tetCode(c, t), tetPartitionCode(static_cast<Label>(100 + tet[0] % 3), static_cast<Label>(100 + tet[1] % 3),
                                              static_cast<Label>(100 + tet[2] % 3), static_cast<Label>(100 + tet[3] % 3)));
  }
}

TEST(ClassifyCell, CellIndex) {
  LabelVolume v = makeVolume(4, 5, 6);
  EXPECT_EQ(classifyCell(v, 2, 3, 4).cell, 2u + 3u * (3u + 4u * 4u));
}

LabelVolume randomVolume(unsigned seed, int n, int labels) {
  LabelVolume v = makeVolume(n, n + 1, n + 2);
  std::mt19937 rng(seed);
  for (int k = 1; k + 1 < v.grid.nz; ++k)
    for (int j = 1; j + 1 < v.grid.ny; ++j)
      for (int i = 1; i + 1 < v.grid.nx; ++i)
        // Blocky so uniform cells are common as well as mixed ones.
        v.labels[v.grid.index(i, j, k)] = static_cast<Label>(((i / 2 + j / 3 + k) % 2 == 0) ? rng() % labels : 1);
  return v;
}

TEST(ClassifyCellsReference, MatchesPerCellAndSorted) {
  for (unsigned seed = 0; seed < 5; ++seed) {
    const LabelVolume v = randomVolume(seed, 9, 4);
    const std::vector<CellCase> cases = classifyCellsReference(v);
    std::vector<CellCase> expected;
    for (int k = 0; k + 1 < v.grid.nz; ++k)
      for (int j = 0; j + 1 < v.grid.ny; ++j)
        for (int i = 0; i + 1 < v.grid.nx; ++i) {
          const CellCase c = classifyCell(v, i, j, k);
          bool differ = false;
          for (int corner = 1; corner < 8; ++corner) differ |= cellCornerLabel(c, corner) != cellCornerLabel(c, 0);
          EXPECT_EQ(differ, c.tetCodes != 0);
          if (c.tetCodes != 0) expected.push_back(c);
        }
    ASSERT_EQ(cases.size(), expected.size());
    ASSERT_FALSE(cases.empty());
    for (std::size_t n = 0; n < cases.size(); ++n) {
      if (n > 0) {
        EXPECT_LT(cases[n - 1].cell, cases[n].cell);
      }
      EXPECT_EQ(std::memcmp(&cases[n], &expected[n], sizeof(CellCase)), 0) << n;
    }
  }
}

TEST(ClassifyCellsReference, IndependentOfThreadCount) {
  const LabelVolume v = randomVolume(42, 14, 5);
  const char* old = std::getenv("SCANSURF_THREADS");
  const std::string saved = old ? old : "";
  std::vector<std::vector<CellCase>> runs;
  for (const char* threads : {"1", "2", "3", "7"}) {
    setenv("SCANSURF_THREADS", threads, 1);
    runs.push_back(classifyCellsReference(v));
  }
  if (old) {
    setenv("SCANSURF_THREADS", saved.c_str(), 1);
  } else {
    unsetenv("SCANSURF_THREADS");
  }
  for (std::size_t r = 1; r < runs.size(); ++r) {
    ASSERT_EQ(runs[r].size(), runs[0].size());
    EXPECT_EQ(std::memcmp(runs[r].data(), runs[0].data(), runs[0].size() * sizeof(CellCase)), 0);
  }
}

}  // namespace
}  // namespace scansurf
