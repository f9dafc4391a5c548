// Constrained smoothing and contour-faithful vertices (issue 3), on the CPU pipeline:
// makeGrid -> referenceScanConvert -> classifyCellsReference -> assembleMesh -> smoothMesh.
#include "geometry/smoothing/smooth_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "geometry/extraction/assembly.h"
#include "geometry/extraction/cell_cases.h"
#include "geometry/extraction/feature_surfaces.h"
#include "geometry/overlaps/overlap_analysis.h"
#include "geometry/smoothing/contour_fit.h"
#include "scansurf/nesting.h"
#include "support/intersections.h"
#include "support/reference_rasterizer.h"
#include "support/shapes.h"
#include "support/surface_checks.h"

namespace scansurf::test {
namespace {

// ---------------------------------------------------------------- exact intersection tests

using Tri = std::array<Point3, 3>;

TEST(Intersections, OrientationIsExactOnNearlyCoplanarPoints) {
  const Point3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_EQ(orient3d(a, b, c, {0.25, 0.25, 0}), 0);
  EXPECT_EQ(orient3d(a, b, c, {0.25, 0.25, 1e-300}), -1);  // above the ccw triangle
  EXPECT_EQ(orient3d(a, b, c, {0.25, 0.25, -1e-300}), 1);
  // Far from the origin, where the naive determinant rounds to garbage.
  const double big = 1e8;
  const Point3 p{big, big, big}, q{big + 1, big, big}, r{big, big + 1, big};
  EXPECT_EQ(orient3d(p, q, r, {big + 0.5, big + 0.5, big}), 0);
  EXPECT_EQ(orient3d(p, q, r, {big + 0.5, big + 0.5, std::nextafter(big, 2 * big)}), -1);
  // A tilted plane (z = x + y): no axis-plane shortcut, the expansions decide.
  const Point3 e{0, 0, 0}, f{1, 0, 1}, g{0, 1, 1};
  EXPECT_EQ(orient3d(e, f, g, {0.5, 0.5, 1}), 0);
  EXPECT_EQ(orient3d(e, f, g, {0.5, 0.5, std::nextafter(1.0, 2.0)}), -1);
  EXPECT_EQ(orient3d(e, f, g, {0.5, 0.5, std::nextafter(1.0, 0.0)}), 1);
  // Four points in one axis plane other than z: exactly 0 (the shortcut), however far out.
  EXPECT_EQ(orient3d({big, 0.1, 0.3}, {big, 0.7, 0.2}, {big, 0.3, 0.9}, {big, 0.5, 0.5}), 0);
  EXPECT_EQ(orient3d({big, 0.1, 0.3}, {big, 0.7, 0.2}, {big, 0.3, 0.9}, {std::nextafter(big, 2 * big), 0.5, 0.5}), -1);
  EXPECT_EQ(orient2d({0.1, 0.1, 0}, {0.2, 0.2, 0}, {0.3, 0.3, 0}, 0, 1),
            orient2d({0.1, 0.1, 0}, {0.2, 0.2, 0}, {0.3, 0.3, 0}, 0, 1));
  EXPECT_EQ(orient2d({1, 1, 0}, {2, 2, 0}, {3, 3, 0}, 0, 1), 0);
}

// PlaneSide shares one plane's minors among many points; its signs must be orient3d's,
// exactly, including on the plane and one ulp off it, near the origin and far from it.
TEST(Intersections, PlaneSideGivesOrient3dsSigns) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  int zero = 0, checked = 0;
  for (const double offset : {0.0, 1e3, 1e8}) {
    for (int plane = 0; plane < 200; ++plane) {
      const auto at = [&](double s) {
        return Point3{offset + s * unit(random), offset + s * unit(random), offset + s * unit(random)};
      };
      // Integer-valued corners where the plane is exact: points on it can be built exactly.
      const Point3 a = {offset + std::round(8 * unit(random)), offset + std::round(8 * unit(random)), offset};
      const Point3 b = {a[0] + 4, a[1] + std::round(4 * unit(random)), a[2] + 2};
      const Point3 c = {a[0] + std::round(4 * unit(random)), a[1] + 4, a[2] + 1};
      const PlaneSide side(a, b, c);
      std::vector<Point3> points = {a, b, c, at(10), at(1e-3)};
      for (const double s : {0.5, 0.25, 2.0}) {  // on the plane: a + s (b - a) + t (c - a), exact here
        const Point3 on = {a[0] + s * (b[0] - a[0]) + 0.5 * (c[0] - a[0]), a[1] + s * (b[1] - a[1]) + 0.5 * (c[1] - a[1]),
                           a[2] + s * (b[2] - a[2]) + 0.5 * (c[2] - a[2])};
        points.push_back(on);
        for (int k = 0; k < 3; ++k) {
          Point3 off = on;
          off[k] = std::nextafter(on[k], on[k] + 1);
          points.push_back(off);
        }
      }
      for (const Point3& d : points) {
        const int expected = orient3d(a, b, c, d);
        ASSERT_EQ(side.side(d), expected) << "plane " << plane << " offset " << offset;
        zero += expected == 0;
        ++checked;
      }
      // A plane of random corners and points rounded onto it: the determinant is at rounding
      // level, so the filter must hand over to the exact fallback.
      const Point3 p = at(1), q = at(1), r = at(1);
      const PlaneSide rounded(p, q, r);
      for (int i = 0; i < 8; ++i) {
        const double s = unit(random), t = unit(random);
        const Point3 d = {p[0] + s * (q[0] - p[0]) + t * (r[0] - p[0]), p[1] + s * (q[1] - p[1]) + t * (r[1] - p[1]),
                          p[2] + s * (q[2] - p[2]) + t * (r[2] - p[2])};
        ASSERT_EQ(rounded.side(d), orient3d(p, q, r, d)) << "plane " << plane << " offset " << offset;
      }
    }
  }
  EXPECT_GE(zero, 600 * 6);            // at least the corners and the points built on the plane
  EXPECT_GE(checked - zero, 600 * 2);  // at least the random points
}

TEST(Intersections, DisjointPiercingAndTouchingTriangles) {
  const Tri a = {{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}};
  const Tri above = {{{0, 0, 1}, {2, 0, 1}, {0, 2, 1}}};
  const Tri pierce = {{{0.5, 0.5, -1}, {0.5, 0.5, 1}, {1.5, -1, 0.2}}};
  const Tri touchVertex = {{{0.5, 0.5, 0}, {0.5, 0.5, 1}, {1, 0.7, 1}}};  // a vertex on a's interior
  const Tri coplanarOverlap = {{{0.5, 0.5, 0}, {3, 0.5, 0}, {0.5, 3, 0}}};
  const Tri coplanarApart = {{{3, 3, 0}, {4, 3, 0}, {3, 4, 0}}};
  EXPECT_FALSE(trianglesCross({0, 1, 2}, a, {3, 4, 5}, above));
  EXPECT_TRUE(trianglesCross({0, 1, 2}, a, {3, 4, 5}, pierce));
  EXPECT_TRUE(trianglesCross({0, 1, 2}, a, {3, 4, 5}, touchVertex));
  EXPECT_TRUE(trianglesCross({0, 1, 2}, a, {3, 4, 5}, coplanarOverlap));
  EXPECT_FALSE(trianglesCross({0, 1, 2}, a, {3, 4, 5}, coplanarApart));
}

TEST(Intersections, SharedEdgesAndVerticesAreNotCrossings) {
  const Tri a = {{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}};
  // Shares edge (0,0,0)-(2,0,0): a hinge is fine, a fold onto a is not.
  EXPECT_FALSE(trianglesCross({0, 1, 2}, a, {0, 1, 3}, {{{0, 0, 0}, {2, 0, 0}, {1, -1, 0.5}}}));
  EXPECT_FALSE(trianglesCross({0, 1, 2}, a, {0, 1, 3}, {{{0, 0, 0}, {2, 0, 0}, {1, -1, 0}}}));
  EXPECT_TRUE(trianglesCross({0, 1, 2}, a, {0, 1, 3}, {{{0, 0, 0}, {2, 0, 0}, {1, 0.5, 0}}}));
  // Shares vertex (0,0,0).
  EXPECT_FALSE(trianglesCross({0, 1, 2}, a, {0, 3, 4}, {{{0, 0, 0}, {-1, 0, 1}, {0, -1, 1}}}));
  EXPECT_FALSE(trianglesCross({0, 1, 2}, a, {0, 3, 4}, {{{0, 0, 0}, {-1, 0, 0}, {0, -1, 0}}}));
  EXPECT_TRUE(trianglesCross({0, 1, 2}, a, {0, 3, 4}, {{{0, 0, 0}, {1, 1, 1}, {1, 1, -1}}}));   // slices through a
  EXPECT_TRUE(trianglesCross({0, 1, 2}, a, {0, 3, 4}, {{{0, 0, 0}, {1, 0.5, 0}, {1, 1, 1}}}));  // an edge inside a's angle
  EXPECT_TRUE(trianglesCross({0, 1, 2}, a, {0, 3, 4}, {{{0, 0, 0}, {3, 0, 0}, {1, -1, 1}}}));   // along a's edge
  // Far side: b's opposite edge passes through a.
  EXPECT_TRUE(trianglesCross({0, 1, 2}, a, {0, 3, 4}, {{{0, 0, 0}, {0.5, 0.5, 1}, {0.6, 0.6, -1}}}));
  EXPECT_TRUE(trianglesCross({0, 1, 2}, a, {0, 1, 2}, a));  // duplicate
}

TEST(Intersections, FindsEveryCrossingPairInAMesh) {
  // Two fans of two triangles each; one triangle of the second pierces one of the first.
  const std::vector<float> p = {0,    0,    0,  2,    0,    0, 0,    2,  0,    2, 2, 0,  // square at z = 0
                                0.5f, 0.5f, -1, 0.5f, 0.5f, 1, 1.5f, -1, 0.2f, 5, 5, 5};
  const std::vector<std::uint32_t> t = {0, 1, 2, 1, 3, 2, 4, 5, 6, 5, 6, 7};
  const IntersectionReport r = findCrossings(p, t);
  EXPECT_EQ(r.crossings, 1u);
  ASSERT_EQ(r.examples.size(), 1u);
  EXPECT_EQ(r.examples[0], (std::pair<std::uint32_t, std::uint32_t>{0, 2}));
  EXPECT_EQ(r.degenerate, 0u);
}

// ---------------------------------------------------------------- the CPU pipeline

SmoothingOptions on() {
  SmoothingOptions o;
  o.enabled = true;
  return o;
}

SmoothingReport smooth(Built& b, const SmoothingOptions& options = on(), int threads = 0) {
  return smoothMesh(b.mesh, b.grid, &b.set, options, threads);
}

// Feature surfaces closed, manifold, oriented, with the expected genus each, and no two
// triangles of the whole multi-label mesh crossing.
void expectSoundSurfaces(const Built& b, const std::vector<int>& genus, const char* when) {
  for (std::size_t f = 0; f < b.features.size(); ++f) {
    const MeshStats s = computeMeshStats(b.mesh.positions, b.features[f].triangles);
    EXPECT_TRUE(s.closed && s.manifold && s.oriented) << b.set.source << " feature " << f << " " << when;
    EXPECT_EQ(s.genus, genus[f]) << b.set.source << " feature " << f << " " << when;
    EXPECT_GT(s.volume, 0) << b.set.source << " feature " << f << " " << when;
  }
  const IntersectionReport r = findCrossings(b.mesh.positions, b.mesh.triangles);
  EXPECT_EQ(r.crossings, 0u) << b.set.source << " " << when;
  EXPECT_EQ(r.degenerate, 0u) << b.set.source << " " << when;
  EXPECT_GT(r.pairsTested, b.mesh.triangleCount()) << "the broad phase must pair up neighbours";
  std::printf("[ figure   ] %-14s %-6s %8zu triangles, %9zu pairs tested exactly, %zu crossing\n", b.set.source.c_str(), when,
              b.mesh.triangleCount(), r.pairsTested, r.crossings);
}

void checkNeverCross(const ContourSet& set, double voxel, const std::vector<int>& genus) {
  Built b = buildCpu(set, voxel);
  ASSERT_EQ(b.mesh.keys.size(), b.mesh.vertexCount());
  expectSoundSurfaces(b, genus, "raw");
  const SmoothingReport r = smooth(b);
  EXPECT_GT(r.sheet + r.fitted, 0u);
  expectSoundSurfaces(b, genus, "smooth");
}

TEST(Smoothing, NestedSpheresNeverCross) { checkNeverCross(nestedSpheresContours(), 1.0, {0, 0}); }
TEST(Smoothing, AbuttingHalvesNeverCross) { checkNeverCross(abuttingContours(10, 6, 2.5), 0.5, {0, 0}); }
TEST(Smoothing, BranchingVesselNeverCrosses) { checkNeverCross(yBranchContours(), 0.5, {0}); }
TEST(Smoothing, ThinBarsOnePixelApartNeverCross) { checkNeverCross(thinBarsContours(2.2), 1.0, {0, 0}); }
TEST(Smoothing, PhantomNeverCrosses) {
  // Every junction kind: abutting organs, nesting, a branch, a hollow vertebra (genus 0 each,
  // the vertebra's two components: skin and cavity).
  checkNeverCross(phantomContours(), 3.0, {0, 0, 0, 0, 0, 0});
}

TEST(Smoothing, CarrierOfEveryVertexHasItAsBarycentre) {
  const Built b = buildCpu(phantomContours(), 3.0);
  std::set<int> counts;
  for (std::uint64_t key : b.mesh.keys) {
    const Carrier c = carrierOfKey(key);
    ASSERT_GE(c.count, 2);
    counts.insert(c.count);
    std::uint64_t sum[3] = {0, 0, 0};
    for (int m = 0; m < c.count; ++m)
      for (int a = 0; a < 3; ++a) sum[a] += static_cast<std::uint64_t>(c.corners[m][a]) * 12;
    EXPECT_EQ(packVertexKey(sum[0] / c.count, sum[1] / c.count, sum[2] / c.count), key);
    for (int m = 1; m < c.count; ++m)  // a chain: each corner steps forward from the previous
      for (int a = 0; a < 3; ++a) EXPECT_GE(c.corners[m][a], c.corners[m - 1][a]);
  }
  EXPECT_EQ(counts, (std::set<int>{2, 3, 4}));  // edges, face centroids, tetrahedron centroids
  EXPECT_EQ(carrierOfKey(packVertexKey(12 * 5 + 6, 12 * 2, 12 * 7)).count, 2);
  EXPECT_EQ(carrierOfKey(packVertexKey(12 * 5, 12 * 2, 12 * 7)).count, 0);          // a voxel centre
  EXPECT_EQ(carrierOfKey(packVertexKey(12 * 5 + 4, 12 * 2 + 6, 12 * 7)).count, 0);  // mixed thirds and halves
}

TEST(Smoothing, SameResultForAnyThreadCount) {
  Built one = buildCpu(yBranchContours(), 0.5);
  Built two = one, three = one;
  smooth(one, on(), 1);
  smooth(two, on(), 2);
  smooth(three, on(), 3);
  EXPECT_EQ(one.mesh.positions, two.mesh.positions);
  EXPECT_EQ(one.mesh.positions, three.mesh.positions);
}

TEST(Smoothing, SuperStepsCoverTheSweepsAskedFor) {
  // 150 plain sweeps' worth of smoothing (the default) in 5 super-steps of 7 stages; a single
  // sweep's worth is one plain sweep; none is none.
  Built b = buildCpu(yBranchContours(), 0.5);
  const Built raw = b;
  EXPECT_EQ(smooth(b).sweeps, 35);
  SmoothingOptions o = on();
  o.iterations = 1;
  b = raw;
  EXPECT_EQ(smooth(b, o).sweeps, 1);
  o.iterations = 0;
  b = raw;
  EXPECT_EQ(smooth(b, o).sweeps, 0);
  EXPECT_EQ(b.mesh.positions.size(), raw.mesh.positions.size());
}

TEST(Smoothing, OptionsSwitchEachPartOff) {
  const Built raw = buildCpu(phantomContours(), 2.0);
  Built off = raw;
  SmoothingOptions o;
  o.enabled = false;
  smooth(off, o);
  EXPECT_EQ(off.mesh.positions, raw.mesh.positions);

  Built noJunctions = raw, full = raw;
  o = on();
  o.junctions = false;
  const SmoothingReport rn = smooth(noJunctions, o);
  const SmoothingReport rf = smooth(full);
  EXPECT_GT(rf.curve, 0u);
  EXPECT_EQ(rn.curve, 0u);
  EXPECT_EQ(rn.fixed, rf.fixed + rf.curve);
  // Junction vertices (triangles of more than one label pair) stay put without junctions.
  std::vector<std::uint32_t> pairOf(raw.mesh.vertexCount(), 0);
  std::vector<char> junction(raw.mesh.vertexCount(), 0);
  for (std::size_t t = 0; t < raw.mesh.triangleCount(); ++t) {
    const std::uint32_t pair = raw.mesh.labels[2 * t] | (static_cast<std::uint32_t>(raw.mesh.labels[2 * t + 1]) << 16);
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = raw.mesh.triangles[3 * t + c];
      if (pairOf[v] != 0 && pairOf[v] != pair) junction[v] = 1;
      pairOf[v] = pair;
    }
  }
  std::size_t junctions = 0, stayed = 0, movedWithJunctions = 0;
  for (std::size_t v = 0; v < raw.mesh.vertexCount(); ++v) {
    if (!junction[v]) continue;
    ++junctions;
    const float* p = &raw.mesh.positions[3 * v];
    stayed += std::equal(p, p + 3, &noJunctions.mesh.positions[3 * v]);
    movedWithJunctions += !std::equal(p, p + 3, &full.mesh.positions[3 * v]);
  }
  EXPECT_GT(junctions, 0u);
  EXPECT_EQ(stayed, junctions);
  EXPECT_GT(movedWithJunctions, 0u);

  Built noFit = raw;
  o = on();
  o.contourFit = false;
  EXPECT_EQ(smooth(noFit, o).fitted, 0u);
  EXPECT_GT(rf.fitted, 0u);
}

// ---------------------------------------------------------------- accuracy

// Between its first and last planes the surface follows the shape the contours give (the
// blend across each pair of planes); beyond them the caps hold the slab rule's half slab, which
// a sphere's or a torus's true cap is not (it stands taller than the shape's pole): the distance
// limits hold between the planes, the volume is the slab rule's.
void reportAccuracy(const char* name, const Built& raw, const Built& smooth, const Distance& distance, double analyticVolume,
                    double meanLimit, double maxLimit) {
  double zLow = 1e300, zHigh = -1e300;
  for (const FeatureSlice& s : smooth.set.features[0].slices) zLow = std::min(zLow, s.z), zHigh = std::max(zHigh, s.z);
  const Accuracy r = accuracy(raw, distance, zLow, zHigh), s = accuracy(smooth, distance, zLow, zHigh);
  const Accuracy whole = accuracy(smooth, distance);
  const double slab = slabVolume(smooth.set.features[0], smooth.grid);
  const Angles ar = minAngles(raw.mesh), as = minAngles(smooth.mesh);
  const double xr = crossSectionError(raw), xs = crossSectionError(smooth);
  std::printf(
      "[ figure   ] %s raw:    distance mean %.4f max %.4f mm between the planes, volume %+.2f %%, cross-section %.4f px, min "
      "angle %.1f (5%% %.1f)\n",
      name, r.mean, r.max, 100 * (r.volume / analyticVolume - 1), xr, ar.min, ar.p5);
  std::printf(
      "[ figure   ] %s smooth: distance mean %.4f max %.4f mm between the planes (%.4f / %.4f with the caps), volume %+.2f "
      "%% (slab rule %+.2f %%), cross-section %.4f px, min angle %.1f (5%% %.1f)\n",
      name, s.mean, s.max, whole.mean, whole.max, 100 * (s.volume / analyticVolume - 1), 100 * (slab / analyticVolume - 1), xs,
      as.min, as.p5);
  EXPECT_LE(s.mean, meanLimit);
  EXPECT_LE(s.max, maxLimit);
  EXPECT_LE(s.mean, r.mean / 3);
  EXPECT_LE(s.max, r.max / 3);
  EXPECT_LT(std::abs(s.volume / slab - 1), 0.01);
  EXPECT_LE(xs, 0.05);
  EXPECT_LT(xs, xr);
}

TEST(SmoothingAccuracy, Sphere20mmAt1mmPixels2mmSlices) {
  const Built raw = buildCpu(sphereContours(10, 2.0), 1.0);
  Built smoothed = raw;
  smooth(smoothed);
  reportAccuracy(
      "sphere r10", raw, smoothed, [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z) - 10; },
      4.0 / 3.0 * std::numbers::pi * 1000, 0.05, 0.35);
}

// Its outermost slabs (z 1 to 3, and -3 to -1) have no plane beyond them to bend the blend: the
// linear blend there is a chord of the tube's circle, up to 0.17 mm inside it.
TEST(SmoothingAccuracy, TorusAt1mmPixels2mmSlices) {
  const double R = 10, r = 4;
  const Built raw = buildCpu(torusContours(R, r, 2.0), 1.0);
  Built smoothed = raw;
  smooth(smoothed);
  reportAccuracy(
      "torus R10 r4", raw, smoothed, [=](double x, double y, double z) { return std::hypot(std::hypot(x, y) - R, z) - r; },
      2 * std::numbers::pi * std::numbers::pi * R * r * r, 0.06, 0.35);
}

// The opt-in angle guard (SmoothingOptions::minAngle): no triangle below the limit, none
// crossing, the same for any thread count; and what it costs against the true surface.
TEST(SmoothingAngles, MinAngleKeepsEveryTriangleAboveItWithoutCrossings) {
  const Built raw = buildCpu(torusContours(10, 4, 2.0), 1.0);
  const auto distance = [](double x, double y, double z) { return std::hypot(std::hypot(x, y) - 10, z) - 4; };
  Built plain = raw;
  smooth(plain);
  const Accuracy a0 = accuracy(plain, distance);
  for (const double limit : {3.0, 15.0}) {
    SmoothingOptions o = on();
    o.minAngle = limit;
    Built guarded = raw, oneThread = raw;
    smooth(guarded, o);
    smooth(oneThread, o, 1);
    EXPECT_EQ(guarded.mesh.positions, oneThread.mesh.positions) << limit;
    const Angles angles = minAngles(guarded.mesh);
    EXPECT_GE(angles.min, limit - 1e-3) << limit;
    EXPECT_EQ(findCrossings(guarded.mesh.positions, guarded.mesh.triangles).crossings, 0u) << limit;
    const Accuracy a = accuracy(guarded, distance);
    EXPECT_LE(a.mean, (limit <= 3 ? 1.1 : 3.0) * a0.mean) << limit;
    EXPECT_LE(crossSectionError(guarded), limit <= 3 ? 0.05 : 0.15) << limit;
    std::printf("[ figure   ] torus R10 r4 min angle %4.1f: smallest %.1f (5%% %.1f), mean distance %.4f mm against %.4f off\n",
                limit, angles.min, angles.p5, a.mean, a0.mean);
  }
}

}  // namespace
}  // namespace scansurf::test

namespace scansurf {
namespace {

// Whether the segment touches the closed square [ci, ci+1] x [cj, cj+1] (Liang-Barsky clip).
bool touchesSquare(double u0, double v0, double u1, double v1, int ci, int cj) {
  double t0 = 0, t1 = 1;
  const double d[2] = {u1 - u0, v1 - v0}, p[2] = {u0, v0}, lo[2] = {double(ci), double(cj)};
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0) {
      if (p[a] < lo[a] || p[a] > lo[a] + 1) return false;
      continue;
    }
    double ta = (lo[a] - p[a]) / d[a], tb = (lo[a] + 1 - p[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

// Contour fitting files each contour segment under the lattice cells it touches: every one of
// them (on corners, along lattice lines, steep and flat), and O(length) of them, not its
// bounding box (a self-crossing star's long diagonals filed 1.4 GB per plane).
TEST(ContourFit, SegmentsAreFiledUnderTheCellsTheyTouch) {
  ShapeRng rng(7);
  const int n = 64;
  std::vector<std::array<double, 4>> segments = {
      {2, 2, 40, 40}, {3, 1, 3, 20}, {1, 5, 30, 5}, {0.5, 0.5, 60.5, 61.25}, {10, 10, 10, 10}};
  for (int i = 0; i < 200; ++i)
    segments.push_back({rng.uniform(0, n - 1), rng.uniform(0, n - 1), rng.uniform(0, n - 1), rng.uniform(0, n - 1)});
  for (const auto& s : segments) {
    std::vector<std::uint64_t> cells;
    appendTouchedCells(s[0], s[1], s[2], s[3], n, n, cells);
    const std::set<std::uint64_t> filed(cells.begin(), cells.end());
    EXPECT_EQ(filed.size(), cells.size()) << "each cell once";
    for (int cj = 0; cj < n; ++cj)
      for (int ci = 0; ci < n; ++ci) {
        if (!touchesSquare(s[0], s[1], s[2], s[3], ci, cj)) continue;
        EXPECT_TRUE(filed.count(std::uint64_t(ci) | (std::uint64_t(cj) << 32)))
            << "cell " << ci << "," << cj << " of (" << s[0] << "," << s[1] << ")-(" << s[2] << "," << s[3] << ")";
      }
    const double length = std::abs(s[2] - s[0]) + std::abs(s[3] - s[1]);
    EXPECT_LE(cells.size(), 2 * length + 8) << "O(length), not the bounding box";
  }
}

}  // namespace
}  // namespace scansurf
