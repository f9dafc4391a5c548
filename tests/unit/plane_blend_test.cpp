// Blended crossings between contour planes that no grid layer separates (plane_blend.h): the
// Hermite blend of a structure's fields, and its round cap where it ends.
#include "geometry/smoothing/plane_blend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/blend_rules.h"
#include "geometry/extraction/assembly.h"
#include "support/shapes.h"

namespace scansurf {
namespace {

// 1 mm pixels over [-20, 20] in x and y, layers 3 mm apart.
Grid gridOf(std::vector<double> layerZ) {
  Grid g;
  g.nx = g.ny = 41;
  g.originX = g.originY = -20;
  g.nz = static_cast<int>(layerZ.size());
  g.layerZ = std::move(layerZ);
  g.planeTolerance = 1e-6;
  return g;
}

// One feature with a circle of each radius on the planes given (centred on the z axis).
ContourSet discs(const std::vector<std::pair<double, double>>& zRadius) {
  ContourSet set;
  set.features.push_back({"disc", {}, {}});
  for (const auto& [z, r] : zRadius) set.features[0].slices.push_back({z, {circleContour({0, 0}, r, 1024)}});
  return set;
}

// The key of the vertex on the vertical grid edge over pixel (i, j) from layer k to k + 1.
std::uint64_t verticalEdge(int i, int j, int k) {
  return packVertexKey(12 * static_cast<std::uint64_t>(i), 12 * static_cast<std::uint64_t>(j),
                       12 * static_cast<std::uint64_t>(k) + 6);
}

double rootOf(double (*f)(double)) {
  double lo = 0, hi = 1;
  for (int i = 0; i < 60; ++i) ((f(0.5 * (lo + hi)) > 0) == (f(0) > 0) ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

TEST(PlaneBlend, TheHermiteBlendKeepsThePlanesValuesAndStaysBetweenThem) {
  EXPECT_DOUBLE_EQ(hermiteBlend(2, -1, -5, 0, 0), 2);
  EXPECT_DOUBLE_EQ(hermiteBlend(2, -1, -5, 0, 1), -1);
  EXPECT_DOUBLE_EQ(hermiteBlend(2, -1, -3, -3, 0.25), 2 - 0.75);  // the chord's tangents: linear
  EXPECT_DOUBLE_EQ(monotoneTangent(2, -1), 0);                    // a turn: flat there
  EXPECT_DOUBLE_EQ(monotoneTangent(-2, -3), -2.4);                // the harmonic mean
  for (const double before : {-6.0, -3.0, -0.5, 0.0, 2.0})
    for (const double after : {-6.0, -3.0, -0.5, 0.0, 2.0}) {
      const double a = 1, b = -2;
      const double ta = monotoneTangent(before, b - a), tb = monotoneTangent(b - a, after);
      for (double t = 0; t <= 1; t += 0.05) {
        const double v = hermiteBlend(a, b, ta, tb, t);
        EXPECT_LE(v, a + 1e-12) << before << " " << after << " " << t;
        EXPECT_GE(v, b - 1e-12) << before << " " << after << " " << t;
      }
    }
}

// Circles of radius 12, 10 and 7 on planes -3, 0 and 3: over x = 9 the fields are 3, 1 and -2,
// so between planes 0 and 3 the surface crosses where 1 - 3t + 0.6 t (1 - t)^2 is zero (the
// tangent -2.4 at plane 0 from the changes -2 and -3, the chord's at plane 3, which has no plane
// after it). Not where the linear blend crosses, at t = 1/3.
TEST(PlaneBlend, AVertexBetweenTwoPlanesGoesWhereTheBlendedFieldIsZero) {
  const Grid grid = gridOf({-6, -3, 0, 3, 6});
  const ContourSet set = discs({{-3, 12}, {0, 10}, {3, 7}});
  const std::vector<std::uint64_t> keys = {verticalEdge(29, 20, 2), verticalEdge(20, 20, 2), verticalEdge(29, 20, 1)};
  const std::vector<Label> labels = {1, 0, 1, 0, 0, 0};
  const BlendedCrossings b = blendedCrossings(grid, set, keys, labels, 1);
  const double expected = rootOf([](double t) { return 1 - 3 * t + 0.6 * t * (1 - t) * (1 - t); });
  EXPECT_NEAR(b.t[0], expected, 1e-3);
  EXPECT_GT(std::abs(expected - 1.0 / 3), 0.02);
  EXPECT_TRUE(b.interior[0]);
  EXPECT_EQ(b.t[1], -1) << "inside on both planes: no crossing";
  EXPECT_EQ(b.t[2], -1) << "background has no contours";
}

// A disc of radius 8 drawn on one plane: its round cap is half an ellipsoid 3/4 of the gap high
// (taper 0), whose cross-section at height u H keeps (1 - u^2) of the disc's area, the pixels
// deeper than some erosion. Over the centre it stands at 3/4 of the gap; over x = 4, where a
// quarter of the pixels lie deeper, at sqrt(3/4) of that; below the plane the same, downward.
TEST(PlaneBlend, WhereAStructureEndsItsVerticesMeetItsRoundCap) {
  const Grid grid = gridOf({-3, 0, 3});
  const ContourSet set = discs({{0, 8}});
  const std::vector<std::uint64_t> keys = {verticalEdge(20, 20, 1), verticalEdge(24, 20, 1), verticalEdge(24, 20, 0),
                                           verticalEdge(30, 20, 1)};
  const std::vector<Label> labels = {1, 0, 1, 0, 0, 1, 1, 0};
  const BlendedCrossings b = blendedCrossings(grid, set, keys, labels, 1);
  EXPECT_NEAR(b.t[0], 0.75, 0.01);
  EXPECT_NEAR(b.t[1], 0.75 * std::sqrt(0.75), 0.03);
  EXPECT_NEAR(b.t[2], 1 - b.t[1], 1e-12);
  EXPECT_FALSE(b.interior[0]);
  EXPECT_EQ(b.t[3], -1) << "outside the disc: no cap over it";
}

}  // namespace
}  // namespace scansurf
