// The triangle shape steps (issue 28): snapping crowded vertices onto voxel centres, choosing
// each quad's diagonal and re-triangulating the cubes' and blocks' fans, on the CPU pipeline:
// makeGrid -> referenceScanConvert -> classifyCellsReference -> assembleMesh -> smoothMesh ->
// shapeTriangles -> restoreVolumes. Every shape the smoothing tests use,
// checked exactly afterwards: both conventions' surfaces, crossings, carriers, shared interfaces,
// angles and counts (printed, and held as bounds), accuracy against the analytic surfaces.
#include "geometry/shape/snapping.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include "geometry/extraction/assembly.h"
#include "geometry/extraction/feature_surfaces.h"
#include "geometry/grid/contour_layers.h"
#include "geometry/shape/cube_fans.h"
#include "geometry/shape/quad_diagonals.h"
#include "geometry/shape/triangle_shape.h"
#include "geometry/shape/volume_restoration.h"
#include "geometry/smoothing/carrier_projection.h"
#include "geometry/smoothing/smooth_mesh.h"
#include "support/intersections.h"
#include "support/shapes.h"
#include "support/surface_checks.h"

namespace scansurf::test {
namespace {

constexpr double kDefaultSnap = SmoothingOptions{}.snap;

struct Snapped {
  TriangleShapeReport report;
  std::size_t flips = 0;
  std::size_t heldBack = 0;  // restoration moves undone to keep a cube's disk unfolded
};

// What the engine runs after relaxation: snapping, the quads' diagonals, the cubes' fans, then
// each feature's volume restored (here to what it enclosed before snapping), its disks unfolded.
Snapped snapAndFlip(Built& b, std::vector<bool> onSheet, double fraction = kDefaultSnap, int threads = 0, bool cubeFans = true) {
  std::vector<double> volumes;
  for (const MeshStats& s : surfaceStats(b, SurfaceConvention::Enclosing)) volumes.push_back(s.volume);
  Snapped out;
  const ShapedTriangles shaped = shapeTriangles(b.mesh, b.grid, fraction, onSheet, cubeFans, threads);
  EXPECT_EQ(onSheet.size(), b.mesh.vertexCount());
  EXPECT_TRUE(disksEmbedded(shaped.disks, b.mesh)) << b.set.source;
  out.report = shaped.report, out.flips = shaped.report.quadsFlipped;
  out.heldBack =
      restoreVolumes(b.mesh, b.grid, b.nesting, volumes, onSheet, contourLayers(b.grid, &b.set), 0, threads, &shaped.disks)
          .heldBack;
  EXPECT_TRUE(disksEmbedded(shaped.disks, b.mesh)) << b.set.source << ": a disk folded in the volume restoration";
  refreshFeatures(b);
  return out;
}

Vec3 positionOf(const MultiLabelMesh& m, std::size_t v) {
  return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
}

// Keys sorted and unique; a voxel-centre vertex sits exactly on its centre, every other one
// strictly inside its carrier.
void expectOnTheLattice(const Built& b) {
  const MultiLabelMesh& m = b.mesh;
  ASSERT_EQ(m.keys.size(), m.vertexCount());
  EXPECT_TRUE(std::adjacent_find(m.keys.begin(), m.keys.end(), std::greater_equal<>()) == m.keys.end());
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const Carrier c = carrierOfKey(m.keys[v]);
    const Vec3 p = positionOf(m, v);
    if (c.count == 0) {
      const int corner[3] = {static_cast<int>((m.keys[v] & kKeyMask) / 12),
                             static_cast<int>(((m.keys[v] >> kKeyBits) & kKeyMask) / 12),
                             static_cast<int>((m.keys[v] >> (2 * kKeyBits)) / 12)};
      const Vec3 at = cornerPosition(b.grid, corner);
      EXPECT_LT(glm::length(p - at), 1e-4) << b.set.source << " vertex " << v;
      continue;
    }
    const Vec3 q = projectIntoCarrier(b.grid, c, p);
    // The clamped projection moves a point already inside by less than a quarter of the margin
    // (its renormalisation); one outside, by more than the margin.
    EXPECT_LT(glm::length(p - q), 0.25 * kCarrierMargin * b.grid.spacingX)
        << b.set.source << " vertex " << v << " left its carrier";
  }
}

// Per voxel-centre vertex, its triangles carry one label pair (snapping never touches a junction).
void expectOneLabelPairAtSnappedPoints(const MultiLabelMesh& m) {
  std::vector<std::set<std::pair<Label, Label>>> pairs(m.vertexCount());
  for (std::size_t t = 0; t < m.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) pairs[m.triangles[3 * t + c]].insert({m.labels[2 * t], m.labels[2 * t + 1]});
  for (std::size_t v = 0; v < m.vertexCount(); ++v)
    if (carrierOfKey(m.keys[v]).count == 0) {
      EXPECT_EQ(pairs[v].size(), 1u) << "vertex " << v;
    }
}

// Smooths, snaps, flips and re-triangulates `set`, checking every promise against the smoothed
// mesh; `fewer`: the most of the smoothed triangle count the three may keep (a bound, printed
// with the figures).
// Volumes within 1 % at any fraction: the restoration after snapping takes back what it moved.
Built checkSnap(const ContourSet& set, double voxel, double fewer, double fraction = kDefaultSnap) {
  Built b = buildCpu(set, voxel);
  const SmoothingReport smoothed = smoothWithDefaults(b);
  const SurfaceSnapshot surfaces = snapshotSurfaces(b);
  const Angles before = minAngles(b.mesh);
  const std::size_t trianglesBefore = b.mesh.triangleCount();
  const auto t0 = std::chrono::steady_clock::now();
  const Snapped s = snapAndFlip(b, smoothed.onSheet, fraction);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const std::string& lost : surfacesLost(b, surfaces, 0.01)) ADD_FAILURE() << set.source << " " << lost;
  const IntersectionReport x = findCrossings(b.mesh.positions, b.mesh.triangles);
  EXPECT_EQ(x.crossings, 0u) << set.source;
  EXPECT_EQ(x.degenerate, 0u) << set.source;
  expectOnTheLattice(b);
  expectOneLabelPairAtSnappedPoints(b.mesh);
  const Angles after = minAngles(b.mesh);
  EXPECT_GE(after.p5, before.p5 - 0.1) << set.source;
  EXPECT_EQ(trianglesBefore - b.mesh.triangleCount(), s.report.removedTriangles + 2 * s.report.fanVerticesRemoved) << set.source;
  EXPECT_LE(s.report.points, s.report.candidates) << set.source;
  EXPECT_LE(static_cast<double>(b.mesh.triangleCount()), fewer * static_cast<double>(trianglesBefore)) << set.source;
  std::printf(
      "[ figure   ] %-14s snap %.2f: %zu points of %zu candidates (%zu not disks), triangles %7zu -> "
      "%7zu (%.2fx), %zu quads flipped, %zu cubes and blocks (%zu vertices; %zu restoration moves undone), min angle "
      "%4.1f -> %4.1f, "
      "5%% %4.1f -> %4.1f; %.3f s\n",
      set.source.c_str(), fraction, s.report.points, s.report.candidates, s.report.candidates - s.report.points, trianglesBefore,
      b.mesh.triangleCount(), static_cast<double>(b.mesh.triangleCount()) / static_cast<double>(trianglesBefore), s.flips,
      s.report.cubeFans, s.report.fanVerticesRemoved, s.heldBack, before.min, after.min, before.p5, after.p5, seconds);
  return b;
}

// ---------------------------------------------------------------- soundness on every shape

TEST(Snapping, NestedSpheres) { checkSnap(nestedSpheresContours(), 1.0, 0.7); }
TEST(Snapping, BranchingVessel) { checkSnap(yBranchContours(), 0.5, 0.75); }
TEST(Snapping, Phantom) { checkSnap(phantomContours(), 3.0, 0.7); }
TEST(Snapping, SphereWithSlicesAsThickAsPixels) { checkSnap(sphereContours(10, 1.0), 1.0, 0.7); }
TEST(Snapping, TheLargestFractionKeepsEveryPromise) {
  checkSnap(nestedSpheresContours(), 1.0, 0.9, 0.45);
  checkSnap(phantomContours(), 3.0, 0.9, 0.45);
}

// Abutting structures still share every interface vertex.
TEST(Snapping, AbuttingHalvesShareTheirInterface) {
  const Built b = checkSnap(abuttingContours(10, 6, 2.5), 0.5, 0.75);
  const InterfaceUse use = interfaceUse(b.mesh, b.features[0], b.features[1], 1, 2);
  EXPECT_GT(use.triangles, 0u);
  EXPECT_EQ(use.unshared, 0u);
}

// Three features meeting on a junction curve: the curve's vertices are never merged (a snapped
// point's star carries one label pair) and every label pair keeps its triangles.
TEST(Snapping, JunctionCurvesWhereThreeFeaturesMeetStay) {
  Built b = buildCpu(threeSectorsContours(), 0.5);
  smoothWithDefaults(b);
  std::set<std::pair<Label, Label>> pairsBefore, pairsAfter;
  for (std::size_t t = 0; t < b.mesh.triangleCount(); ++t) pairsBefore.insert({b.mesh.labels[2 * t], b.mesh.labels[2 * t + 1]});
  std::set<std::uint64_t> curveKeys;  // vertices whose triangles carry more than one label pair
  {
    std::vector<std::set<std::pair<Label, Label>>> pairs(b.mesh.vertexCount());
    for (std::size_t t = 0; t < b.mesh.triangleCount(); ++t)
      for (int c = 0; c < 3; ++c) pairs[b.mesh.triangles[3 * t + c]].insert({b.mesh.labels[2 * t], b.mesh.labels[2 * t + 1]});
    for (std::size_t v = 0; v < b.mesh.vertexCount(); ++v)
      if (pairs[v].size() > 1) curveKeys.insert(b.mesh.keys[v]);
  }
  ASSERT_FALSE(curveKeys.empty());
  const Built snapped = checkSnap(threeSectorsContours(), 0.5, 0.8);
  for (std::size_t t = 0; t < snapped.mesh.triangleCount(); ++t)
    pairsAfter.insert({snapped.mesh.labels[2 * t], snapped.mesh.labels[2 * t + 1]});
  EXPECT_EQ(pairsAfter, pairsBefore);
  const std::set<std::uint64_t> keysAfter(snapped.mesh.keys.begin(), snapped.mesh.keys.end());
  for (std::uint64_t k : curveKeys) EXPECT_TRUE(keysAfter.count(k)) << "junction vertex " << k << " merged";
}

// Bars 1.4 and 2.2 pixels wide: a snapped point never joins a bar's two walls (a star of two
// sheets is no disk), so no bar collapses through itself (surfacesLost: same components, genus).
TEST(Snapping, ThinBarsDoNotCollapseThroughThemselves) {
  for (const double fraction : {kDefaultSnap, 0.2}) {
    checkSnap(thinBarsContours(1.4), 1.0, 0.9, fraction);
    checkSnap(thinBarsContours(2.2), 1.0, 0.9, fraction);
  }
}

TEST(Snapping, SameResultForAnyThreadCount) {
  Built one = buildCpu(phantomContours(), 2.0);
  const SmoothingReport smoothed = smoothWithDefaults(one);
  Built two = one, seven = one;
  snapAndFlip(one, smoothed.onSheet, 0.2, 1);
  snapAndFlip(two, smoothed.onSheet, 0.2, 2);
  snapAndFlip(seven, smoothed.onSheet, 0.2, 7);
  EXPECT_EQ(one.mesh.positions, two.mesh.positions);
  EXPECT_EQ(one.mesh.triangles, two.mesh.triangles);
  EXPECT_EQ(one.mesh.keys, two.mesh.keys);
  EXPECT_EQ(one.mesh.positions, seven.mesh.positions);
  EXPECT_EQ(one.mesh.triangles, seven.mesh.triangles);
}

TEST(Snapping, ZeroChangesNothing) {
  Built b = buildCpu(yBranchContours(), 0.5);
  smoothWithDefaults(b);
  const MultiLabelMesh before = b.mesh;
  std::vector<bool> onSheet(b.mesh.vertexCount(), true);
  const TriangleShapeReport r = snapToLattice(b.mesh, b.grid, 0, onSheet);
  EXPECT_EQ(r.points, 0u);
  EXPECT_EQ(b.mesh.positions, before.positions);
  EXPECT_EQ(b.mesh.triangles, before.triangles);
}

// ---------------------------------------------------------------- cubes' fans

// A mesh whose triangles are not in cell order could hold one cube's triangles in two places:
// no cube is touched then.
TEST(CubeFans, TrianglesOutOfCellOrderAreLeftAlone) {
  Built b = buildCpu(sphereContours(10, 2.0), 1.0);
  std::vector<bool> onSheet = smoothWithDefaults(b).onSheet;
  std::swap_ranges(b.mesh.triangles.begin(), b.mesh.triangles.begin() + 3, b.mesh.triangles.end() - 3);
  std::swap_ranges(b.mesh.labels.begin(), b.mesh.labels.begin() + 2, b.mesh.labels.end() - 2);
  const MultiLabelMesh before = b.mesh;
  EXPECT_EQ(retriangulateCubeFans(b.mesh, b.grid, onSheet).count(), 0u);
  EXPECT_EQ(b.mesh.triangles, before.triangles);
  EXPECT_EQ(b.mesh.positions, before.positions);
}

// Each disk loses its inner vertices and twice as many triangles; the rims stay as they were (every rim edge was an
// edge before), and a vertex moved so that its disk folds is put back.
TEST(CubeFans, RimsStayAndAFoldIsPutBack) {
  Built b = buildCpu(sphereContours(10, 2.0), 1.0);
  std::vector<bool> onSheet = smoothWithDefaults(b).onSheet;
  const MultiLabelMesh relaxed = b.mesh;
  std::vector<bool> sheet = onSheet;
  snapToLattice(b.mesh, b.grid, kDefaultSnap, sheet);
  chooseQuadDiagonals(b.mesh);
  const MultiLabelMesh fans = b.mesh;
  const CubeDisks disks = retriangulateCubeFans(b.mesh, b.grid, sheet);
  ASSERT_GT(disks.count(), 100u);
  EXPECT_GT(disks.removedVertices, disks.count()) << "blocks of 2 x 2 cubes lose more than one vertex";
  EXPECT_EQ(fans.vertexCount() - b.mesh.vertexCount(), disks.removedVertices);
  EXPECT_EQ(fans.triangleCount() - b.mesh.triangleCount(), 2 * disks.removedVertices);
  std::set<std::pair<std::uint64_t, std::uint64_t>> edgesBefore;
  for (std::size_t t = 0; t < fans.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c)
      edgesBefore.insert({fans.keys[fans.triangles[3 * t + c]], fans.keys[fans.triangles[3 * t + (c + 1) % 3]]});
  for (std::size_t d = 0; d < disks.count(); ++d)
    for (std::uint32_t i = disks.rimStart[d]; i < disks.rimStart[d + 1]; ++i) {
      const std::uint32_t next = i + 1 < disks.rimStart[d + 1] ? i + 1 : disks.rimStart[d];
      EXPECT_TRUE(edgesBefore.count({b.mesh.keys[disks.rims[i]], b.mesh.keys[disks.rims[next]]})) << "disk " << d;
    }
  ASSERT_TRUE(disksEmbedded(disks, b.mesh));
  const std::vector<float> before = b.mesh.positions;
  const std::uint32_t moved = disks.rims[disks.rimStart[0]], other = disks.rims[disks.rimStart[0] + 2];
  std::copy(&before[3 * std::size_t{other}], &before[3 * std::size_t{other}] + 3, &b.mesh.positions[3 * std::size_t{moved}]);
  EXPECT_FALSE(disksEmbedded(disks, b.mesh));
  EXPECT_GE(keepDisksEmbedded(disks, b.mesh, before), 1u);
  EXPECT_TRUE(disksEmbedded(disks, b.mesh));
  EXPECT_EQ(b.mesh.positions, before);
}

// Boxes two layers thick: some disks span two layers, and no triangle crosses a lattice layer
// (each keeps to one side of its box's middle layer, so the layer cuts the disk along its chord,
// which the accuracy test below holds within 0.05 pixel of the contours).
TEST(CubeFans, DisksTwoLayersThickCutAlongTheirMiddleLayer) {
  for (const auto& [set, voxel] : {std::pair{sphereContours(10, 2.0), 1.0}, std::pair{torusContours(10, 4, 2.0), 1.0},
                                   std::pair{phantomContours(), 3.0}, std::pair{nestedSpheresContours(), 1.0}}) {
    Built b = buildCpu(set, voxel);
    std::vector<bool> sheet = smoothWithDefaults(b).onSheet;
    snapToLattice(b.mesh, b.grid, kDefaultSnap, sheet);
    chooseQuadDiagonals(b.mesh);
    const CubeDisks disks = retriangulateCubeFans(b.mesh, b.grid, sheet);
    const auto zKey = [&](std::uint32_t v) { return b.mesh.keys[v] >> (2 * kKeyBits); };
    std::size_t thick = 0;
    for (std::size_t d = 0; d < disks.count(); ++d) {
      const auto [low, high] = std::minmax_element(&disks.rims[disks.rimStart[d]], &disks.rims[disks.rimStart[d + 1]],
                                                   [&](std::uint32_t u, std::uint32_t v) { return zKey(u) < zKey(v); });
      thick += zKey(*high) - zKey(*low) == 24;
    }
    std::printf("[ figure   ] %-14s %zu of %zu disks two layers thick\n", set.source.c_str(), thick, disks.count());
    EXPECT_GT(thick, disks.count() / 100) << set.source;
    for (std::size_t t = 0; t < b.mesh.triangleCount(); ++t) {
      const std::uint32_t* c = &b.mesh.triangles[3 * t];
      const auto [low, high] = std::minmax({zKey(c[0]), zKey(c[1]), zKey(c[2])});
      ASSERT_LE(high - low, 12u) << set.source << " triangle " << t << " crosses a layer";
    }
  }
}

// ---------------------------------------------------------------- accuracy

// The sphere and torus at 1 mm pixels, 2 mm slices: snapping at the default keeps the mean
// distance to the true surface within 10 % of the smoothed one, and the cross-sections on the
// contour planes within 0.05 pixel of the contours.
TEST(SnappingAccuracy, SphereAndTorusWithinTenPercentOfSmoothed) {
  const struct {
    ContourSet set;
    Distance distance;
  } shapes[] = {
      {sphereContours(10, 2.0), [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z) - 10; }},
      {torusContours(10, 4, 2.0), [](double x, double y, double z) { return std::hypot(std::hypot(x, y) - 10, z) - 4; }},
  };
  for (const auto& shape : shapes) {
    Built b = buildCpu(shape.set, 1.0);
    const std::vector<bool> onSheet = smoothWithDefaults(b).onSheet;
    const Accuracy smoothed = accuracy(b, shape.distance);
    const double sectionBefore = crossSectionError(b);
    snapAndFlip(b, onSheet);
    const Accuracy snapped = accuracy(b, shape.distance);
    const double section = crossSectionError(b);
    std::printf("[ figure   ] %-14s mean / max distance %.4f / %.4f -> %.4f / %.4f mm, cross-section %.4f -> %.4f px\n",
                shape.set.source.c_str(), smoothed.mean, smoothed.max, snapped.mean, snapped.max, sectionBefore, section);
    EXPECT_LE(snapped.mean, 1.1 * smoothed.mean) << shape.set.source;
    EXPECT_LE(section, 0.05) << shape.set.source;
    EXPECT_LT(std::abs(snapped.volume / smoothed.volume - 1), 0.005) << shape.set.source;
  }
}

// Slices thinner than the pixels (a sphere r 20 at 1 mm pixels, 0.5 mm slices): the fans'
// tolerance is a share of the finest lattice spacing in the box, here the layer gap, so they
// bring the surface closer to the true one than snapping and the diagonals alone leave it (gaps
// thinner than a pixel are relaxed, not blended: geometry/smoothing/plane_blend.h).
TEST(SnappingAccuracy, FansKeepTheAccuracyAtSlicesThinnerThanThePixels) {
  const Distance sphere = [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z) - 20; };
  Built fans = buildCpu(sphereContours(20, 0.5), 1.0);
  const std::vector<bool> onSheet = smoothWithDefaults(fans).onSheet;
  Built snapped = fans;
  const double relaxed = accuracy(fans, sphere).mean;
  snapAndFlip(snapped, onSheet, kDefaultSnap, 0, false);
  snapAndFlip(fans, onSheet);
  const double withoutFans = accuracy(snapped, sphere).mean, withFans = accuracy(fans, sphere).mean;
  std::printf(
      "[ figure   ] sphere r 20, 0.5 mm slices: mean distance %.4f relaxed, %.4f snapped, %.4f with the fans (%zu -> %zu "
      "triangles)\n",
      relaxed, withoutFans, withFans, snapped.mesh.triangleCount(), fans.mesh.triangleCount());
  EXPECT_LE(withFans, 0.97 * withoutFans);  // 0.93 with the gap in the tolerance, 1.00 with the pixel alone
  EXPECT_LT(fans.mesh.triangleCount(), snapped.mesh.triangleCount());
}

// Slices as thin as the pixels or thinner: the surface's own error shrinks with the spacing and
// the full fraction would cost it 18 % (1 mm) and 25 % (0.5 mm) of its mean distance; the
// fraction the engine uses there (snapFractionFor) keeps it within the 10 %, and at slices two
// pixels apart it is the option's own.
TEST(SnappingAccuracy, ThinSlicesSnapLessAndKeepTheAccuracy) {
  const Distance sphere = [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z) - 20; };
  for (const double slice : {2.0, 1.0, 0.5}) {
    Built b = buildCpu(sphereContours(20, slice), 1.0);
    const std::vector<bool> onSheet = smoothWithDefaults(b).onSheet;
    const double relaxed = accuracy(b, sphere).mean;
    const std::size_t before = b.mesh.triangleCount();
    const double fraction = snapFractionFor(b.grid, contourLayers(b.grid, &b.set), kDefaultSnap);
    EXPECT_NEAR(fraction, kDefaultSnap * std::min(1.0, slice / 2), 1e-9) << slice;
    snapAndFlip(b, onSheet, fraction);
    const double shaped = accuracy(b, sphere).mean;
    std::printf(
        "[ figure   ] sphere r 20, %.1f mm slices: fraction %.4f, mean distance %.4f -> %.4f mm (%+.1f %%), %zu -> %zu "
        "triangles\n",
        slice, fraction, relaxed, shaped, 100 * (shaped / relaxed - 1), before, b.mesh.triangleCount());
    EXPECT_LE(shaped, 1.1 * relaxed) << slice;
    EXPECT_LT(4 * b.mesh.triangleCount(), 3 * before) << slice;
  }
}

// ---------------------------------------------------------------- quads' diagonals

// One (2+2) tetrahedron of the Freudenthal cube at voxel (5, 5, 5): corners p0 < p1 < p2 < p3
// stepping x, y, z; labels 1 at p0, p1 and 2 at p2, p3. Its quad joins the points on edges
// p0p2, p0p3, p1p3, p1p2, split by assembly along one diagonal.
MultiLabelMesh oneQuad(float nearP0, bool splitAlongFirst) {
  const int p[4][3] = {{5, 5, 5}, {6, 5, 5}, {6, 6, 5}, {6, 6, 6}};
  const auto edgeKey = [&](int a, int b) {
    return packVertexKey(static_cast<std::uint64_t>(6 * (p[a][0] + p[b][0])), static_cast<std::uint64_t>(6 * (p[a][1] + p[b][1])),
                         static_cast<std::uint64_t>(6 * (p[a][2] + p[b][2])));
  };
  const auto along = [&](int a, int b, float t) {
    std::vector<float> out(3);
    for (int k = 0; k < 3; ++k)
      out[static_cast<std::size_t>(k)] = static_cast<float>(p[a][k]) + t * static_cast<float>(p[b][k] - p[a][k]);
    return out;
  };
  // Vertices in key order: edge keys sorted.
  struct V {
    std::uint64_t key;
    std::vector<float> at;
  };
  std::vector<V> v = {{edgeKey(0, 2), along(0, 2, nearP0)},
                      {edgeKey(0, 3), along(0, 3, nearP0)},
                      {edgeKey(1, 3), along(1, 3, 0.5f)},
                      {edgeKey(1, 2), along(1, 2, 0.5f)}};
  MultiLabelMesh m;
  for (const V& x : v) m.keys.push_back(x.key), m.positions.insert(m.positions.end(), x.at.begin(), x.at.end());
  // The quad's cycle 0 (p0p2) -> 1 (p0p3) -> 2 (p1p3) -> 3 (p1p2).
  m.triangles = splitAlongFirst ? std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<std::uint32_t>{0, 1, 3, 1, 2, 3};
  m.labels = {1, 2, 1, 2};
  return m;
}

TEST(QuadDiagonals, EitherSplitEndsAsTheBetterOne) {
  // The p0 side pinched to 10 % of its edges: the two splits differ in their sharpest corner.
  MultiLabelMesh first = oneQuad(0.1f, true), second = oneQuad(0.1f, false);
  const double before[2] = {minAngles(first).min, minAngles(second).min};
  std::printf("[ figure   ] one quad: smallest angle %.2f split one way, %.2f the other\n", before[0], before[1]);
  ASSERT_GT(std::abs(before[0] - before[1]), 0.2);
  const std::size_t flips = chooseQuadDiagonals(first, 1) + chooseQuadDiagonals(second, 1);
  EXPECT_EQ(flips, 1u) << "only the worse split is flipped";
  EXPECT_NEAR(minAngles(first).min, std::max(before[0], before[1]), 1e-6);
  EXPECT_NEAR(minAngles(second).min, std::max(before[0], before[1]), 1e-6);
  for (const MultiLabelMesh& m : {first, second}) {
    MultiLabelMesh again = m;
    EXPECT_EQ(chooseQuadDiagonals(again, 1), 0u) << "a chosen diagonal stays";
    const MeshStats s = computeMeshStats(m.positions, m.triangles);
    EXPECT_EQ(s.triangles, 2u);
    EXPECT_EQ(s.components, 1);
  }
}

}  // namespace
}  // namespace scansurf::test
