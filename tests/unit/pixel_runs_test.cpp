// The CPU rasterizer of overlap analysis and the label volume's masks against the reference
// rasterizer that the GPU scan conversion is checked against pixel for pixel: identical.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/overlaps/pixel_runs.h"
#include "support/reference_rasterizer.h"
#include "support/shapes.h"

namespace scansurf {
namespace {

Grid testGrid(int nx, int ny) {
  Grid g;
  g.nx = nx;
  g.ny = ny;
  g.nz = 3;
  g.originX = -0.25;
  g.originY = 0.5;
  g.spacingX = 0.75;
  g.spacingY = 0.5;
  g.layerZ = {-1, 0, 1};
  return g;
}

// The reference's layer 1 for one feature, as a 0/1 image.
std::vector<std::uint8_t> referenceMask(const std::vector<Contour>& contours, const Grid& grid) {
  ContourSet set;
  set.features.push_back({"f", {}, {{0.0, contours}}});
  const LabelVolume v = test::referenceScanConvert(set, grid, {0}, 8);
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny));
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) mask[static_cast<std::size_t>(j * grid.nx + i)] = v.at(i, j, 1) != 0;
  return mask;
}

std::vector<std::uint8_t> runMask(const std::vector<PixelRun>& runs, const Grid& grid) {
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny));
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (r > 0) {
      EXPECT_TRUE(runs[r - 1].row < runs[r].row || runs[r - 1].end < runs[r].begin) << "sorted, apart";
    }
    for (int i = runs[r].begin; i < runs[r].end; ++i) mask[static_cast<std::size_t>(runs[r].row * grid.nx + i)] = 1;
  }
  return mask;
}

TEST(PixelRuns, RandomOverlappingPolygonsMatchTheReference) {
  const Grid grid = testGrid(61, 47);
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    ShapeRng rng(seed);
    std::vector<Contour> contours;
    const int count = 1 + static_cast<int>(seed % 3);
    for (int c = 0; c < count; ++c)
      contours.push_back(randomPolygon(rng, {rng.uniform(8, 36), rng.uniform(6, 18)}, 1, 12, 5 + static_cast<int>(seed % 20)));
    const std::vector<PixelRun> runs = rasterizeSlice(contours, grid, 8);
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_EQ(runMask(runs, grid), referenceMask(contours, grid));
    EXPECT_EQ(pixelCount(runs), sharedPixels(runs, runs));
  }
}

// Vertices on the half-pixel lattice: many centres exactly on edges, where the top-left rule
// decides; polygons reaching beyond the grid are clipped.
TEST(PixelRuns, LatticeAlignedAndClippedPolygonsMatchTheReference) {
  const Grid grid = testGrid(24, 20);
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    ShapeRng rng(seed);
    Contour c;
    const int n = 3 + static_cast<int>(seed % 7);
    for (int p = 0; p < n; ++p) {
      const double i = std::floor(rng.uniform(-4, 52)) * 0.5, j = std::floor(rng.uniform(-4, 44)) * 0.5;
      c.points.push_back({grid.originX + (i - 0.5) * grid.spacingX, grid.originY + (j - 0.5) * grid.spacingY});
    }
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_EQ(runMask(rasterizeSlice({c}, grid, 8), grid), referenceMask({c}, grid));
  }
}

TEST(PixelRuns, SharedAndTouchingRuns) {
  const std::vector<PixelRun> a{{2, 0, 5}, {3, 1, 4}};
  EXPECT_EQ(sharedPixels(a, {{2, 3, 9}, {3, 0, 2}}), 3u);
  EXPECT_FALSE(touchInPlane(a, {{2, 7, 9}}));
  EXPECT_TRUE(touchInPlane(a, {{2, 5, 9}}));   // side by side on a row
  EXPECT_TRUE(touchInPlane(a, {{4, 3, 4}}));   // the row below
  EXPECT_FALSE(touchInPlane(a, {{4, 4, 6}}));  // only diagonally
}

}  // namespace
}  // namespace scansurf
