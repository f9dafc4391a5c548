// Planar helpers and coverage: exact small cases and properties.
#include "geometry/contours/polygon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "geometry/contours/crossings.h"
#include "geometry/grid/coverage.h"
#include "support/shapes.h"

namespace scansurf {
namespace {

Contour square(double x0, double y0, double x1, double y1) { return Contour{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}; }

TEST(Polygon, BoundingBox) {
  const Contour c{{{1, 2}, {-3, 5}, {4, -1}}};
  const Box2 b = boundingBox(c);
  EXPECT_EQ(b.minX, -3);
  EXPECT_EQ(b.maxX, 4);
  EXPECT_EQ(b.minY, -1);
  EXPECT_EQ(b.maxY, 5);
  EXPECT_TRUE(Box2{}.empty());
  EXPECT_TRUE(boundingBox(ContourSet{}).empty());
  ContourSet set = abuttingContours(10, 2);
  const Box2 all = boundingBox(set);
  EXPECT_NEAR(all.minX, -10, 0.01);  // arc vertices need not hit the extreme
  EXPECT_NEAR(all.maxX, 10, 0.01);
  EXPECT_DOUBLE_EQ(all.minY, -10);
  EXPECT_DOUBLE_EQ(all.maxY, 10);
}

TEST(Polygon, SignedArea) {
  EXPECT_EQ(signedArea(square(0, 0, 2, 3)), 6);
  Contour cw = square(0, 0, 2, 3);
  std::reverse(cw.points.begin(), cw.points.end());
  EXPECT_EQ(signedArea(cw), -6);
  EXPECT_EQ(signedArea(Contour{{{0, 0}, {1, 1}}}), 0);
  EXPECT_NEAR(signedArea(circleContour({5, 5}, 10, 4096)), M_PI * 100, 0.01);
  // Far from the origin, precision holds.
  EXPECT_EQ(signedArea(square(1e6, 1e6, 1e6 + 2, 1e6 + 3)), 6);
}

TEST(Polygon, RegionAreaSubtractsHoles) {
  const std::vector<Contour> ring{square(0, 0, 10, 10), square(2, 2, 4, 4)};
  EXPECT_EQ(regionArea(ring), 96);
  const std::vector<Contour> islandInHole{square(0, 0, 10, 10), square(2, 2, 8, 8), square(4, 4, 5, 5)};
  EXPECT_EQ(regionArea(islandInHole), 100 - 36 + 1);
}

TEST(Crossings, ASimpleContourDoesNotCrossItself) {
  EXPECT_FALSE(firstSelfCrossing(square(0, 0, 2, 2)));
  EXPECT_TRUE(crossingHeights(std::vector<Contour>{square(0, 0, 1, 1), square(2, 2, 3, 3)}).empty());
}

TEST(Crossings, ABowTieCrossesAtItsMiddleAndKeepsBothWings) {
  const Contour bowTie{{{0, 0}, {2, 2}, {2, 0}, {0, 2}}};
  const auto at = firstSelfCrossing(bowTie);
  ASSERT_TRUE(at);
  EXPECT_DOUBLE_EQ(at->x, 1);
  EXPECT_DOUBLE_EQ(at->y, 1);
  EXPECT_DOUBLE_EQ(signedArea(bowTie), 0);                        // the wings cancel in the shoelace sum
  EXPECT_DOUBLE_EQ(regionArea(std::vector<Contour>{bowTie}), 2);  // even-odd: both wings
}

TEST(Crossings, OverlappingContoursOfOneSliceCancelWhereBothCover) {
  const std::vector<Contour> two{square(0, 0, 2, 2), square(1, 1, 3, 3)};
  EXPECT_EQ(crossingHeights(two).size(), 2u);
  EXPECT_DOUBLE_EQ(regionArea(two), 6);  // 4 + 4, less the shared unit square twice
}

TEST(Crossings, AStarCountsWhatEvenOddFillingCovers) {
  // A pentagram: its centre is covered twice and so is outside by the even-odd rule.
  Contour spiral;
  for (int k = 0; k < 5; ++k) {
    const double a = M_PI / 2 + k * 4 * M_PI / 5;
    spiral.points.push_back({2 + 2 * std::cos(a), 2 + 2 * std::sin(a)});
  }
  EXPECT_TRUE(firstSelfCrossing(spiral));
  // Even-odd area by a fine raster of cell centres.
  double raster = 0;
  const int n = 800;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (insideRegion(std::vector<Contour>{spiral}, {4.0 * (i + 0.5) / n, 4.0 * (j + 0.5) / n})) raster += 16.0 / (n * n);
  EXPECT_NEAR(evenOddArea(std::vector<Contour>{spiral}), raster, 0.02);
  EXPECT_NEAR(regionArea(std::vector<Contour>{spiral}), raster, 0.02);
}

TEST(Polygon, InsideSquare) {
  const std::vector<Contour> s{square(0, 0, 2, 2)};
  EXPECT_TRUE(insideRegion(s, {1, 1}));
  EXPECT_FALSE(insideRegion(s, {3, 1}));
  EXPECT_FALSE(insideRegion(s, {-1, 1}));
  EXPECT_FALSE(insideRegion(s, {1, 3}));
  // Half-open rule: left and bottom edges in, right and top edges out.
  EXPECT_TRUE(insideRegion(s, {0, 1}));
  EXPECT_FALSE(insideRegion(s, {2, 1}));
  EXPECT_TRUE(insideRegion(s, {1, 0}));
  EXPECT_FALSE(insideRegion(s, {1, 2}));
  EXPECT_TRUE(insideRegion(s, {0, 0}));
  EXPECT_FALSE(insideRegion(s, {2, 2}));
  EXPECT_FALSE(insideRegion(s, {0, 2}));
  EXPECT_FALSE(insideRegion(s, {2, 0}));
}

TEST(Polygon, EvenOddHole) {
  const std::vector<Contour> ring{square(0, 0, 10, 10), square(3, 3, 7, 7)};
  EXPECT_TRUE(insideRegion(ring, {1, 5}));
  EXPECT_FALSE(insideRegion(ring, {5, 5}));
  EXPECT_FALSE(insideRegion(ring, {11, 5}));
  // Direction of the contours does not matter.
  std::vector<Contour> flipped = ring;
  std::reverse(flipped[1].points.begin(), flipped[1].points.end());
  EXPECT_EQ(insideRegion(flipped, {5, 5}), insideRegion(ring, {5, 5}));
  EXPECT_EQ(insideRegion(flipped, {1, 5}), insideRegion(ring, {1, 5}));
}

TEST(Polygon, VertexOnScanlineCountsOnce) {
  // A diamond: the ray from the centre passes exactly through the right vertex.
  const std::vector<Contour> diamond{Contour{{{0, -1}, {1, 0}, {0, 1}, {-1, 0}}}};
  EXPECT_TRUE(insideRegion(diamond, {0, 0}));
  EXPECT_TRUE(insideRegion(diamond, {-0.5, 0}));
  EXPECT_FALSE(insideRegion(diamond, {-2, 0}));
  // A spike touching the ray at a local maximum y: not a crossing.
  const std::vector<Contour> spike{Contour{{{0, 0}, {4, 0}, {4, 4}, {3, 4}, {2, 1}, {1, 4}, {0, 4}}}};
  EXPECT_TRUE(insideRegion(spike, {0.5, 1}));
  EXPECT_TRUE(insideRegion(spike, {0.5, 3}));
  EXPECT_FALSE(insideRegion(spike, {2, 3}));
}

TEST(Polygon, RegionIndexAnswersAsInsideRegionEverywhere) {
  // A ring with a hole, a star crossing itself, a flat contour (one row) and a single point:
  // probes at every vertex, every edge's midpoint, every row's bounds and on a fine lattice.
  std::vector<Contour> ring{square(0, 0, 10, 10), square(3, 3, 7, 7)};
  Contour star;
  for (int i = 0; i < 5; ++i)
    star.points.push_back({5 + 4 * std::cos(4 * std::numbers::pi * i / 5), 5 + 4 * std::sin(4 * std::numbers::pi * i / 5)});
  const std::vector<std::vector<Contour>> regions{
      ring, {star}, {Contour{{{0, 2}, {4, 2}, {8, 2}}}}, {Contour{{{1, 1}}}}, {square(0, 0, 10, 10), star}};
  for (const auto& region : regions) {
    const RegionIndex index(region);
    std::vector<Point2> probes;
    for (const Contour& c : region)
      for (std::size_t i = 0; i < c.points.size(); ++i) {
        const Point2 a = c.points[i], b = c.points[(i + 1) % c.points.size()];
        probes.push_back(a), probes.push_back({0.5 * (a.x + b.x), 0.5 * (a.y + b.y)});
      }
    for (int i = -4; i <= 44; ++i)
      for (int j = -4; j <= 44; ++j) probes.push_back({0.25 * i, 0.25 * j});
    for (int i = 0; i <= 1000; ++i) probes.push_back({5.0, 0.01 * i});  // every row's bounds, near enough
    for (const Point2& p : probes) ASSERT_EQ(index.inside(p), insideRegion(region, p)) << p.x << ", " << p.y;
  }
}

TEST(Polygon, SharedEdgePointBelongsToExactlyOne) {
  // Two triangles sharing the diagonal, given in opposite directions.
  const std::vector<Contour> a{Contour{{{0, 0}, {3, 0}, {3, 7}}}};
  const std::vector<Contour> b{Contour{{{0, 0}, {3, 7}, {0, 7}}}};
  for (int i = 1; i < 70; ++i) {
    const double y = i * 0.1;
    const Point2 p{3.0 / 7.0 * y, y};
    EXPECT_NE(insideRegion(a, p), insideRegion(b, p)) << "y=" << y;
  }
  // Abutting halves of a disc: every sample is in at most one, and inside the disc in one.
  const ContourSet halves = abuttingContours(10, 1);
  const auto& l = halves.features[0].slices[0].contours;
  const auto& r = halves.features[1].slices[0].contours;
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j) {
      const Point2 p{i * 0.25, j * 0.25};
      EXPECT_FALSE(insideRegion(l, p) && insideRegion(r, p));
      if (std::hypot(p.x, p.y) < 9.5) {
        EXPECT_TRUE(insideRegion(l, p) || insideRegion(r, p));
      }
    }
}

TEST(Polygon, EdgeCrossingIsDirectionIndependent) {
  const Point2 a{0.1, 0.3}, b{7.7, 9.1};
  for (double y : {0.3, 1.0, 4.4, 9.0}) EXPECT_EQ(edgeCrossingX(a, b, y), edgeCrossingX(b, a, y));
}

TEST(Polygon, OnBoundary) {
  const std::vector<Contour> s{square(0, 0, 2, 2)};
  EXPECT_TRUE(onBoundary(s, {2, 1}, 1e-9));
  EXPECT_TRUE(onBoundary(s, {0, 0}, 1e-9));
  EXPECT_FALSE(onBoundary(s, {1, 1}, 1e-9));
  EXPECT_TRUE(onBoundary(s, {1, 2.05}, 0.1));
}

TEST(Polygon, RandomPolygonsInsideMatchesArea) {
  // Property: the fraction of a fine sample grid inside approximates the polygon's area.
  ShapeRng rng(42);
  for (int t = 0; t < 5; ++t) {
    const std::vector<Contour> poly{randomPolygon(rng, {0, 0}, 2, 5, 12)};
    int inside = 0;
    const double h = 0.05;
    for (double x = -5; x < 5; x += h)
      for (double y = -5; y < 5; y += h) inside += insideRegion(poly, {x + h / 2, y + h / 2});
    EXPECT_NEAR(inside * h * h, std::abs(signedArea(poly[0])), 0.5);
  }
}

Grid unitGrid(int n) {
  Grid g;
  g.nx = g.ny = n;
  g.nz = 1;
  g.originX = g.originY = 0;
  g.spacingX = g.spacingY = 1;
  g.layerZ = {0};
  return g;
}

TEST(Coverage, FindsContoursBetweenPixelCentres) {
  ContourSet set;
  set.source = "tiny.json";
  Feature f{"speck", std::nullopt, {}};
  f.slices.push_back(FeatureSlice{2.5, {square(1.2, 1.2, 1.8, 1.8), square(2.5, 2.5, 4.5, 4.5)}});
  set.features.push_back(f);
  const auto messages = findUncoveredContours(set, unitGrid(8));
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_NE(messages[0].find("tiny.json"), std::string::npos);
  EXPECT_NE(messages[0].find("\"speck\""), std::string::npos);
  EXPECT_NE(messages[0].find("z=2.5"), std::string::npos);
  EXPECT_NE(messages[0].find("contour 0"), std::string::npos);
}

TEST(Coverage, HalfOpenRuleAtPixelCentres) {
  const Grid g = unitGrid(8);
  EXPECT_TRUE(coversPixelCentre(square(2, 2, 2.5, 2.5), g));   // centre (2,2) on the lower-left corner
  EXPECT_FALSE(coversPixelCentre(square(1.5, 1.5, 2, 2), g));  // centre on the upper-right corner
  EXPECT_FALSE(coversPixelCentre(square(20, 20, 30, 30), g));  // off the grid
  EXPECT_TRUE(coversPixelCentre(square(-5, -5, 50, 50), g));   // covers the whole grid
  // A thin sliver along a row of centres but between columns.
  EXPECT_FALSE(coversPixelCentre(square(3.1, 0, 3.9, 7), g));
}

TEST(Coverage, AgreesWithInsideRegion) {
  ShapeRng rng(7);
  const Grid g = unitGrid(16);
  for (int t = 0; t < 200; ++t) {
    const Contour c = randomPolygon(rng, {rng.uniform(0, 15), rng.uniform(0, 15)}, 0.1, 1.5, 6);
    bool any = false;
    for (int i = 0; i < 16 && !any; ++i)
      for (int j = 0; j < 16 && !any; ++j) any = insideRegion(std::span(&c, 1), {double(i), double(j)});
    EXPECT_EQ(coversPixelCentre(c, g), any) << t;
  }
}

}  // namespace
}  // namespace scansurf
