// makeGrid and layerOfZ: exact layouts for small cases, uneven z, errors.
#include "scansurf/grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/shapes.h"

namespace scansurf {
namespace {

Contour rect(double x0, double y0, double x1, double y1) { return Contour{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}; }

// One feature, a rectangle [0,10]x[0,4] on each z.
ContourSet rectangles(std::vector<double> zs, Contour c = rect(0, 0, 10, 4)) {
  ContourSet set;
  set.source = "rects";
  Feature f{"box", std::nullopt, {}};
  for (double z : zs) f.slices.push_back(FeatureSlice{z, {c}});
  set.features.push_back(f);
  return set;
}

TEST(Grid, VoxelSizeExact) {
  GridOptions o;
  o.voxelSize = 1;
  const auto g = makeGrid(rectangles({0, 2, 4}), o);
  ASSERT_TRUE(g) << g.error().message;
  // 11 interior centres over x in [0,10], 5 over y in [0,4], plus one background each side.
  EXPECT_EQ(g->nx, 13);
  EXPECT_EQ(g->ny, 7);
  EXPECT_EQ(g->nz, 5);
  EXPECT_DOUBLE_EQ(g->originX, -1);
  EXPECT_DOUBLE_EQ(g->originY, -1);
  EXPECT_DOUBLE_EQ(g->spacingX, 1);
  EXPECT_DOUBLE_EQ(g->spacingY, 1);
  EXPECT_EQ(g->layerZ, (std::vector<double>{-2, 0, 2, 4, 6}));
  EXPECT_EQ(g->voxelCount(), 13u * 7u * 5u);
  EXPECT_EQ(g->index(1, 2, 3), 1u + 13u * (2u + 7u * 3u));
}

TEST(Grid, VoxelSizeCentresOnBox) {
  GridOptions o;
  o.voxelSize = 3;  // extent 10 needs ceil(10/3)+1 = 5 centres spanning 12, centred: 5 - 6 = -1
  const auto g = makeGrid(rectangles({1}), o);
  ASSERT_TRUE(g);
  EXPECT_EQ(g->nx, 7);
  EXPECT_DOUBLE_EQ(g->originX, -1 - 3);
  // y: extent 4 -> ceil(4/3)+1 = 3 centres spanning 6, centred on 2: first at -1.
  EXPECT_EQ(g->ny, 5);
  EXPECT_DOUBLE_EQ(g->originY, -1 - 3);
  // A single slice pads at the in-plane spacing.
  EXPECT_EQ(g->layerZ, (std::vector<double>{-2, 1, 4}));
}

TEST(Grid, CountsMapBoxOntoCentresOneAndNMinus2) {
  GridOptions o;
  o.nx = 13;
  o.ny = 5;
  const auto g = makeGrid(rectangles({0, 1}), o);
  ASSERT_TRUE(g);
  EXPECT_EQ(g->nx, 13);
  EXPECT_EQ(g->ny, 5);
  EXPECT_DOUBLE_EQ(g->spacingX, 1);
  EXPECT_DOUBLE_EQ(g->spacingY, 2);
  EXPECT_DOUBLE_EQ(g->originX + 1 * g->spacingX, 0);
  EXPECT_DOUBLE_EQ(g->originX + 11 * g->spacingX, 10);
  EXPECT_DOUBLE_EQ(g->originY + 1 * g->spacingY, 0);
  EXPECT_DOUBLE_EQ(g->originY + 3 * g->spacingY, 4);
}

TEST(Grid, DefaultIsSquarePixelsAlongLongerSide) {
  const auto g = makeGrid(rectangles({0}, rect(0, 0, 253, 100)), GridOptions{});
  ASSERT_TRUE(g);
  EXPECT_EQ(g->nx, GridOptions::kDefaultPixels);
  EXPECT_DOUBLE_EQ(g->spacingX, 1);
  EXPECT_DOUBLE_EQ(g->spacingY, 1);
  EXPECT_EQ(g->ny, 103);
  EXPECT_DOUBLE_EQ(g->originX, -1);
  EXPECT_DOUBLE_EQ(g->originY, -1);
  const auto tall = makeGrid(rectangles({0}, rect(0, 0, 10, 506)), GridOptions{});
  ASSERT_TRUE(tall);
  EXPECT_EQ(tall->ny, 256);
  EXPECT_DOUBLE_EQ(tall->spacingY, 2);
  EXPECT_EQ(tall->nx, 8);  // ceil(10/2)+1 = 6 centres + 2
}

TEST(Grid, UnevenAndMergedSlices) {
  ContourSet set = rectangles({0, 1, 5});
  Feature other{"other", std::nullopt, {}};
  other.slices.push_back(FeatureSlice{1.0004, {rect(1, 1, 2, 2)}});  // same plane as 1
  other.slices.push_back(FeatureSlice{7.5, {rect(1, 1, 2, 2)}});
  set.features.push_back(other);
  GridOptions o;
  o.voxelSize = 1;
  const auto g = makeGrid(set, o);
  ASSERT_TRUE(g);
  EXPECT_EQ(g->layerZ, (std::vector<double>{-1, 0, 1, 5, 7.5, 10}));
  EXPECT_EQ(g->nz, 6);
  EXPECT_EQ(layerOfZ(*g, 1.0004, kDefaultSliceTolerance), 2);
  EXPECT_EQ(layerOfZ(*g, 5, kDefaultSliceTolerance), 3);
  EXPECT_EQ(layerOfZ(*g, -1, 1e-9), 0);
  EXPECT_EQ(layerOfZ(*g, 10, 1e-9), 5);
  EXPECT_EQ(layerOfZ(*g, 3, kDefaultSliceTolerance), -1);
  EXPECT_EQ(layerOfZ(*g, 100, kDefaultSliceTolerance), -1);
  EXPECT_EQ(layerOfZ(*g, -100, kDefaultSliceTolerance), -1);
  EXPECT_EQ(layerOfZ(*g, 4.9, 0.5), 3);
  EXPECT_EQ(layerOfZ(*g, 0.6, 1), 2);  // nearest of two within tolerance
}

TEST(Grid, LayersStrictlyIncreaseForGeneratedShapes) {
  for (const ContourSet& set : {sphereContours(10, 2.5), torusContours(20, 5, 1), phantomContours()}) {
    const auto g = makeGrid(set, GridOptions{});
    ASSERT_TRUE(g) << set.source;
    EXPECT_EQ(g->nz, static_cast<int>(g->layerZ.size()));
    for (int k = 1; k < g->nz; ++k) EXPECT_LT(g->layerZ[k - 1], g->layerZ[k]);
    EXPECT_LE(std::max(g->nx, g->ny), GridOptions::kDefaultPixels);
    EXPECT_EQ(std::max(g->nx, g->ny), GridOptions::kDefaultPixels) << set.source;
  }
}

TEST(Grid, Errors) {
  const ContourSet set = rectangles({0});
  auto fails = [&](GridOptions o, Errc code) {
    const auto g = makeGrid(set, o);
    EXPECT_FALSE(g);
    if (!g) {
      EXPECT_EQ(g.error().code, code) << g.error().message;
    }
  };
  GridOptions o;
  o.voxelSize = -1;
  fails(o, Errc::InvalidArgument);
  o.voxelSize = std::numeric_limits<double>::infinity();
  fails(o, Errc::InvalidArgument);
  o.voxelSize = std::numeric_limits<double>::quiet_NaN();
  fails(o, Errc::InvalidArgument);
  o.voxelSize = 1e-4;  // 100001 pixels
  fails(o, Errc::InvalidArgument);
  o.voxelSize = 1;
  o.nx = o.ny = 8;
  fails(o, Errc::InvalidArgument);  // both set
  o = {};
  o.nx = 3;
  o.ny = 8;
  fails(o, Errc::InvalidArgument);
  o.nx = 8;
  o.ny = 0;
  fails(o, Errc::InvalidArgument);  // only one set
  o.ny = 20000;
  fails(o, Errc::InvalidArgument);
  o.ny = -4;
  fails(o, Errc::InvalidArgument);
  o = {};
  o.sliceTolerance = -1;
  fails(o, Errc::InvalidArgument);

  // A zero extent along y cannot be mapped onto pixel counts.
  GridOptions counts;
  counts.nx = counts.ny = 8;
  const auto flat = makeGrid(rectangles({0}, Contour{{{0, 0}, {10, 0}, {5, 0}}}), counts);
  ASSERT_FALSE(flat);
  EXPECT_EQ(flat.error().code, Errc::InvalidInput);
  // ... but a voxel size still works for it.
  GridOptions size;
  size.voxelSize = 1;
  EXPECT_TRUE(makeGrid(rectangles({0}, Contour{{{0, 0}, {10, 0}, {5, 0}}}), size));
  EXPECT_FALSE(makeGrid(ContourSet{}, size));
}

}  // namespace
}  // namespace scansurf
