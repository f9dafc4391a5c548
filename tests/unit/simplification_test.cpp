// Verified simplification of the separating-surface network (issue 28), on the CPU pipeline:
// makeGrid -> referenceScanConvert -> classifyCellsReference -> assembleMesh -> smoothMesh ->
// simplifyMesh. Every shape the smoothing tests use, checked exactly afterwards; the collapses
// and the patch checks on small hand-made patches.
#include "geometry/simplification/simplify_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "geometry/extraction/feature_surfaces.h"
#include "geometry/grid/contour_layers.h"
#include "geometry/mesh/crossing_search.h"
#include "geometry/mesh/triangle_intersection.h"
#include "geometry/simplification/edge_collapse.h"
#include "geometry/simplification/patch_checks.h"
#include "geometry/smoothing/smooth_mesh.h"
#include "support/intersections.h"
#include "support/shapes.h"
#include "support/surface_checks.h"

namespace scansurf::test {
namespace {

SimplificationOptions simplifyOn() {
  SimplificationOptions o;
  o.enabled = true;
  return o;
}

SimplificationReport simplify(Built& b, const SimplificationOptions& options = simplifyOn(), int threads = 0) {
  const SimplificationReport r = simplifyMesh(b.mesh, b.grid, contourLayers(b.grid, &b.set), options, threads);
  refreshFeatures(b);
  return r;
}

using Position = std::array<float, 3>;
using PositionEdge = std::pair<Position, Position>;

Position positionOf(const MultiLabelMesh& m, std::uint32_t v) {
  return {m.positions[3 * std::size_t{v}], m.positions[3 * std::size_t{v} + 1], m.positions[3 * std::size_t{v} + 2]};
}

// Every edge as a pair of positions (smaller first), with the label pairs of its triangles.
std::map<PositionEdge, std::set<std::pair<Label, Label>>> edgesByPosition(const MultiLabelMesh& m) {
  std::map<PositionEdge, std::set<std::pair<Label, Label>>> out;
  for (std::size_t t = 0; t < m.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) {
      Position a = positionOf(m, m.triangles[3 * t + c]), b = positionOf(m, m.triangles[3 * t + (c + 1) % 3]);
      if (b < a) std::swap(a, b);
      out[{a, b}].insert({m.labels[2 * t], m.labels[2 * t + 1]});
    }
  return out;
}

// Junction edges (triangles of more than one label pair), by position.
std::set<PositionEdge> junctionEdges(const MultiLabelMesh& m) {
  std::set<PositionEdge> out;
  for (const auto& [e, pairs] : edgesByPosition(m))
    if (pairs.size() > 1) out.insert(e);
  return out;
}

// Edges with both ends on one contour plane, by position.
std::set<PositionEdge> planeEdges(const Built& b) {
  std::set<PositionEdge> out;
  for (const auto& [e, pairs] : edgesByPosition(b.mesh))
    if (e.first[2] == e.second[2] && b.grid.layerOfPlane(e.first[2]) >= 0 &&
        contourLayers(b.grid, &b.set)[b.grid.layerOfPlane(e.first[2])])
      out.insert(e);
  return out;
}

std::map<std::pair<Label, Label>, std::size_t> trianglesByPair(const MultiLabelMesh& m) {
  std::map<std::pair<Label, Label>, std::size_t> out;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) ++out[{m.labels[2 * t], m.labels[2 * t + 1]}];
  return out;
}

// Smooths and simplifies `set`, checking every promise against the smoothed mesh; `fewer`: the
// most the triangle count may keep (a bound, printed with the figures).
Built checkSimplify(const ContourSet& set, double voxel, double fewer) {
  Built b = buildCpu(set, voxel);
  smoothWithDefaults(b);
  const Built smoothed = b;
  const SurfaceSnapshot surfaces = snapshotSurfaces(b);
  const Angles anglesBefore = minAngles(b.mesh);
  const auto t0 = std::chrono::steady_clock::now();
  const SimplificationReport r = simplify(b);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(r.ran);
  EXPECT_TRUE(b.mesh.keys.empty());
  EXPECT_EQ(r.trianglesAfter, b.mesh.triangleCount());
  for (const std::string& lost : surfacesLost(b, surfaces, 0.01)) ADD_FAILURE() << set.source << " " << lost;
  const auto pairsBefore = trianglesByPair(smoothed.mesh), pairsAfter = trianglesByPair(b.mesh);
  EXPECT_EQ(pairsAfter.size(), pairsBefore.size()) << set.source << ": every label pair keeps triangles";
  EXPECT_EQ(junctionEdges(b.mesh), junctionEdges(smoothed.mesh)) << set.source << ": junction curves edge for edge";
  EXPECT_EQ(planeEdges(b), planeEdges(smoothed)) << set.source << ": contour-plane cross-sections edge for edge";
  const IntersectionReport x = findCrossings(b.mesh.positions, b.mesh.triangles);
  EXPECT_EQ(x.crossings, 0u) << set.source;
  EXPECT_EQ(x.degenerate, 0u) << set.source;
  const Angles a = minAngles(b.mesh);
  EXPECT_GE(a.min, anglesBefore.min - 1e-3) << set.source << ": no triangle sharper than the sharpest before";
  EXPECT_LE(static_cast<double>(r.trianglesAfter), fewer * static_cast<double>(r.trianglesBefore)) << set.source;
  std::printf(
      "[ figure   ] %-14s triangles %7zu -> %7zu (%.2fx), min angle %5.1f -> %5.1f, 5%% %5.1f -> %5.1f; %zu patches, %zu "
      "refused, %zu crossing; %.3f s\n",
      set.source.c_str(), r.trianglesBefore, r.trianglesAfter,
      static_cast<double>(r.trianglesAfter) / static_cast<double>(r.trianglesBefore), anglesBefore.min, a.min, anglesBefore.p5,
      a.p5, r.patches, r.refused, r.crossing, seconds);
  return b;
}

// ---------------------------------------------------------------- soundness on every shape

TEST(Simplification, NestedSpheres) { checkSimplify(nestedSpheresContours(), 1.0, 0.75); }
TEST(Simplification, AbuttingHalves) { checkSimplify(abuttingContours(10, 6, 2.5), 0.5, 0.7); }
TEST(Simplification, BranchingVessel) { checkSimplify(yBranchContours(), 0.5, 0.85); }
TEST(Simplification, Phantom) { checkSimplify(phantomContours(), 1.0, 0.65); }
TEST(Simplification, ThinBarsOnePixelApart) { checkSimplify(thinBarsContours(2.2), 1.0, 0.85); }
TEST(Simplification, FeatureThinnerThanTwoVoxelsDoesNotCollapseThroughItself) {
  const Built b = checkSimplify(thinBarsContours(1.4), 1.0, 0.85);
  for (const FeatureSurface& f : b.features) EXPECT_GT(computeMeshStats(b.mesh.positions, f.triangles).volume, 0);
}
TEST(Simplification, SphereAtPixelsEqualToTheSlices) { checkSimplify(sphereContours(10, 1.0), 1.0, 0.8); }

// Three features meeting along the axis of a cylinder: the junction curves stay edge for edge
// (checkSimplify), and so do their meeting points.
TEST(Simplification, JunctionCurvesWhereThreeFeaturesMeet) {
  const ContourSet set = threeSectorsContours();
  const Built b = checkSimplify(set, 0.5, 0.8);
  std::set<std::set<std::pair<Label, Label>>> kinds;
  for (const auto& [e, pairs] : edgesByPosition(b.mesh))
    if (pairs.size() > 1) kinds.insert(pairs);
  EXPECT_TRUE(kinds.count({{1, 2}, {1, 3}, {2, 3}})) << "the three sectors still meet along the axis";
}

// ---------------------------------------------------------------- accuracy, determinism

TEST(SimplificationAccuracy, SphereAndTorusWithinATenthMoreDistance) {
  const auto sphere = [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z) - 20; };
  const auto torus = [](double x, double y, double z) { return std::hypot(std::hypot(x, y) - 10, z) - 4; };
  for (const auto& [set, distance] :
       {std::pair{sphereContours(20, 2.0), Distance(sphere)}, std::pair{torusContours(10, 4, 2.0), Distance(torus)}}) {
    Built b = buildCpu(set, 1.0);
    smoothWithDefaults(b);
    const Accuracy before = accuracy(b, distance);
    const double sectionBefore = crossSectionError(b);
    const SimplificationReport r = simplify(b);
    const Accuracy after = accuracy(b, distance);
    const double sectionAfter = crossSectionError(b);
    std::printf(
        "[ figure   ] %-14s 1 mm / 2 mm: %zu -> %zu triangles; mean distance %.4f -> %.4f mm, max %.4f -> %.4f; "
        "cross-section %.4f -> %.4f px\n",
        set.source.c_str(), r.trianglesBefore, r.trianglesAfter, before.mean, after.mean, before.max, after.max, sectionBefore,
        sectionAfter);
    EXPECT_LE(after.mean, 1.1 * before.mean) << set.source;
    EXPECT_LE(after.max, before.max + 0.05) << set.source;
    EXPECT_NEAR(after.volume, before.volume, 0.005 * before.volume) << set.source;
    EXPECT_LE(sectionAfter, sectionBefore + 1e-6) << set.source;
  }
}

// The face normals' error against the true sphere (issue 28's smoothness measure). The mesh's
// normals point from the lower label (background) into the higher: inward here.
std::pair<double, double> normalErrors(const MultiLabelMesh& m) {
  const NormalErrors e = sphereNormalErrors(m.positions, m.triangles, -1);
  return {e.mean, e.p95};
}

TEST(SimplificationAccuracy, FaceNormalsOnTheSphereAt1mmPixels3mmSlices) {
  Built b = buildCpu(sphereContours(20, 3.0), 1.0);
  smoothWithDefaults(b);
  const auto [mean0, p95_0] = normalErrors(b.mesh);
  const SimplificationReport r = simplify(b);
  const auto [mean1, p95_1] = normalErrors(b.mesh);
  std::printf(
      "[ figure   ] sphere r 20, 1 mm / 3 mm: face normal error mean %.1f -> %.1f deg, 95th percentile %.1f -> %.1f "
      "(%zu -> %zu faces)\n",
      mean0, mean1, p95_0, p95_1, r.trianglesBefore, r.trianglesAfter);
  EXPECT_LE(mean1, mean0 + 0.5);
  EXPECT_LE(p95_1, p95_0 + 2.0);
  // Patches that meet a vertex from two sides simplify too, leaving that vertex's triangles.
  EXPECT_EQ(r.refused, 0u);
}

TEST(Simplification, SameResultForAnyThreadCount) {
  Built one = buildCpu(phantomContours(), 2.0);
  smoothWithDefaults(one);
  Built two = one, many = one;
  simplify(one, simplifyOn(), 1);
  simplify(two, simplifyOn(), 2);
  simplify(many, simplifyOn(), 7);
  EXPECT_EQ(one.mesh.positions, two.mesh.positions);
  EXPECT_EQ(one.mesh.triangles, two.mesh.triangles);
  EXPECT_EQ(one.mesh.labels, two.mesh.labels);
  EXPECT_EQ(one.mesh.triangles, many.mesh.triangles);
}

TEST(Simplification, OffLeavesTheMeshAsItIs) {
  Built b = buildCpu(sphereContours(10, 2.0), 1.0);
  smoothWithDefaults(b);
  const MultiLabelMesh before = b.mesh;
  const SimplificationReport r = simplify(b, SimplificationOptions{});
  EXPECT_FALSE(r.ran);
  EXPECT_EQ(b.mesh.positions, before.positions);
  EXPECT_EQ(b.mesh.triangles, before.triangles);
  EXPECT_EQ(b.mesh.keys, before.keys);
}

TEST(Simplification, LongerEdgesAndLooserTolerancesGiveFewerTriangles) {
  Built base = buildCpu(sphereContours(20, 2.0), 1.0);
  smoothWithDefaults(base);
  std::size_t last = base.mesh.triangleCount() + 1;
  for (const auto& [tolerance, edge] : {std::pair{0.02, 1.0}, std::pair{0.05, 2.0}, std::pair{0.2, 4.0}}) {
    Built b = base;
    SimplificationOptions o = simplifyOn();
    o.tolerance = tolerance, o.edgeLength = edge;
    const SimplificationReport r = simplify(b, o);
    EXPECT_LT(r.trianglesAfter, last) << tolerance << " " << edge;
    last = r.trianglesAfter;
  }
}

// ---------------------------------------------------------------- collapses and patch checks

// A flat n x n grid of squares split in two, in z = 0 (2 n^2 triangles, normals up).
struct Flat {
  std::vector<float> positions;
  std::vector<std::uint32_t> triangles;
  std::vector<char> border;
};

Flat flatGrid(int n, double spacing) {
  Flat f;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      f.positions.insert(f.positions.end(), {static_cast<float>(i * spacing), static_cast<float>(j * spacing), 0.0f});
      f.border.push_back(i == 0 || j == 0 || i == n || j == n);
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      f.triangles.insert(f.triangles.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
  return f;
}

TEST(EdgeCollapse, FlatPatchMergesDownToTheEdgeLengthAndKeepsItsBorder) {
  const Flat f = flatGrid(12, 0.25);
  const std::vector<int> noPlane(f.border.size(), -1);
  const std::vector<std::uint32_t> after = collapseEdges(f.positions, f.triangles, f.border, noPlane, {0.01, 1.0, 15});
  EXPECT_LT(after.size(), f.triangles.size() / 2);
  EXPECT_EQ(checkPatch(f.positions, noPlane, f.triangles, after), PatchVerdict::Kept);
  for (std::size_t i = 0; i < after.size(); i += 3) {
    const auto p = [&](int c) { return &f.positions[3 * std::size_t{after[i + c]}]; };
    for (int c = 0; c < 3; ++c) EXPECT_LE(std::hypot(p(c)[0] - p((c + 1) % 3)[0], p(c)[1] - p((c + 1) % 3)[1]), 1.0 + 1e-6);
  }
  // Everything locked: nothing moves.
  const std::vector<char> all(f.border.size(), 1);
  EXPECT_EQ(collapseEdges(f.positions, f.triangles, all, noPlane, {0.01, 1.0, 20}).size(), f.triangles.size());
}

TEST(EdgeCollapse, CurvedPatchKeepsWithinTheDistanceBound) {
  Flat f = flatGrid(16, 0.25);  // bent onto a cylinder of radius 2 about the y axis
  for (std::size_t v = 0; v < f.positions.size() / 3; ++v) {
    const double x = f.positions[3 * v] - 2, a = x / 2;
    f.positions[3 * v] = static_cast<float>(2 * std::sin(a)), f.positions[3 * v + 2] = static_cast<float>(2 * std::cos(a));
  }
  const std::vector<int> noPlane(f.border.size(), -1);
  const std::vector<std::uint32_t> tight = collapseEdges(f.positions, f.triangles, f.border, noPlane, {1e-4, 2.0, 0});
  const std::vector<std::uint32_t> loose = collapseEdges(f.positions, f.triangles, f.border, noPlane, {0.2, 2.0, 0});
  EXPECT_LT(loose.size(), tight.size());
  // Tight, only collapses along the axis are free: every centroid stays within a chord's sag.
  for (std::size_t i = 0; i < tight.size(); i += 3) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) c[d] += f.positions[3 * std::size_t{tight[i + k]} + d] / 3;
    EXPECT_LE(2 - std::hypot(c[0], c[2]), 0.01);
  }
}

TEST(EdgeCollapse, NoEdgeAlongAContourPlaneThatWasNotThere) {
  Flat f = flatGrid(8, 0.25);  // stood up: the row j = 0 lies on a contour plane
  for (std::size_t v = 0; v < f.positions.size() / 3; ++v) std::swap(f.positions[3 * v + 1], f.positions[3 * v + 2]);
  std::vector<int> plane(f.border.size(), -1);
  for (int i = 0; i <= 8; ++i) plane[static_cast<std::size_t>(i)] = 3;
  std::vector<char> locked(f.border.size(), 0);
  for (std::size_t v = 0; v < locked.size(); ++v) locked[v] = plane[v] >= 0 || f.border[v];
  const std::vector<std::uint32_t> after = collapseEdges(f.positions, f.triangles, locked, plane, {0.01, 4.0, 0});
  EXPECT_LT(after.size(), f.triangles.size());
  EXPECT_EQ(checkPatch(f.positions, plane, f.triangles, after), PatchVerdict::Kept);
}

// The crossing search against every pair tested exactly: a soup of small triangles sharing
// corners from one pool (so that pairs meet at shared vertices and edges too), with new
// queries (simplification's first round) and with old ones only (its later rounds).
TEST(CrossingSearch, FindsThePairsEveryPairTestGives) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(0, 6), offset(-1, 1);
  std::vector<float> positions;
  for (int v = 0; v < 240; ++v) {
    const float x = coordinate(random), y = coordinate(random), z = coordinate(random);
    for (int k = 0; k < 3; ++k) positions.push_back(k == 0 ? x : k == 1 ? y : z);
  }
  std::vector<std::uint32_t> triangles;
  std::uniform_int_distribution<std::uint32_t> corner(0, 79), anyCorner(0, 239);
  for (std::uint32_t t = 0; t < 200; ++t) {  // each from one pool corner and two others near it
    const std::uint32_t a = corner(random);
    triangles.push_back(a);
    for (int c = 0; c < 2; ++c) {
      const std::uint32_t v = static_cast<std::uint32_t>(positions.size() / 3);
      const bool shared = random() % 3 == 0;
      if (const std::uint32_t w = anyCorner(random) % 80; shared && w != a && w != triangles.back()) {
        triangles.push_back(w);
        continue;
      }
      for (int k = 0; k < 3; ++k) positions.push_back(positions[3 * a + k] + offset(random));
      triangles.push_back(v);
    }
  }
  const std::size_t count = triangles.size() / 3;
  const auto cornersOf = [&](std::size_t t) {
    std::array<Point3, 3> p;
    for (int c = 0; c < 3; ++c)
      p[c] = Point3{positions[3 * triangles[3 * t + c]], positions[3 * triangles[3 * t + c] + 1],
                    positions[3 * triangles[3 * t + c] + 2]};
    return p;
  };
  std::vector<char> isNew(count), oldQueries(count, 0);
  for (std::size_t t = 0; t < count; ++t) isNew[t] = random() % 2, oldQueries[t] = !isNew[t] && random() % 4 == 0;
  for (const std::vector<char>& query : {isNew, oldQueries}) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> expected;
    for (std::uint32_t a = 0; a < count; ++a)
      for (std::uint32_t b = 0; b < count && query[a]; ++b) {
        if (b == a || (query[b] && b < a) || !(isNew[a] || isNew[b]) || (!isNew[b] && isDegenerate(cornersOf(b)))) continue;
        const std::array<std::uint32_t, 3> ia{triangles[3 * a], triangles[3 * a + 1], triangles[3 * a + 2]};
        const std::array<std::uint32_t, 3> ib{triangles[3 * b], triangles[3 * b + 1], triangles[3 * b + 2]};
        if (trianglesCross(ia, cornersOf(a), ib, cornersOf(b))) expected.insert({a, b});
      }
    for (const double cell : {0.5, 2.0, 8.0})
      for (const int threads : {1, 2}) {
        std::set<std::pair<std::uint32_t, std::uint32_t>> found;
        for (const auto& [a, b] : crossingPairs(positions, triangles, query, isNew, cell, threads)) found.insert({a, b});
        EXPECT_EQ(found, expected) << "cell " << cell << ", " << threads << " threads";
      }
    std::printf("[ figure   ] %zu crossing pairs among %zu queries\n", expected.size(),
                static_cast<std::size_t>(std::count(query.begin(), query.end(), 1)));
    EXPECT_GT(expected.size(), 3u);  // the soup does cross
  }
}

TEST(PatchChecks, EachLossIsNamed) {
  const Flat f = flatGrid(2, 1.0);  // 9 vertices, 8 triangles; vertex 4 in the middle
  const std::vector<int> noPlane(9, -1);
  const std::vector<std::uint32_t>& t = f.triangles;
  EXPECT_EQ(checkPatch(f.positions, noPlane, t, t), PatchVerdict::Kept);
  std::vector<std::uint32_t> flipped = t;
  std::swap(flipped[1], flipped[2]);
  EXPECT_EQ(checkPatch(f.positions, noPlane, t, flipped), PatchVerdict::NotOriented);
  const std::vector<std::uint32_t> lost(t.begin() + 3, t.end());
  EXPECT_EQ(checkPatch(f.positions, noPlane, t, lost), PatchVerdict::Border);
  std::vector<float> collinear = f.positions;
  collinear[3 * 4 + 1] = 0;  // the middle vertex onto the row below: triangle 0, 1, 4 degenerate
  EXPECT_EQ(checkPatch(collinear, noPlane, t, t), PatchVerdict::Degenerate);
  // Vertices 0 and 2 on a contour plane, not joined; 4 joined to all eight (a fan). Replacing
  // the fan's triangles 0-1-4 and 1-2-4 by 0-1-2 and 0-2-4 keeps border and topology but joins
  // 0 and 2 along the plane (vertex 1 lowered so that 0-1-2 is a triangle).
  std::vector<float> lowered = f.positions;
  lowered[3 * 1 + 1] = -0.5f;
  std::vector<int> plane(9, -1);
  plane[0] = plane[2] = 0;
  const std::vector<std::uint32_t> fan = {0, 1, 4, 1, 2, 4, 2, 5, 4, 5, 8, 4, 8, 7, 4, 7, 6, 4, 6, 3, 4, 3, 0, 4};
  const std::vector<std::uint32_t> chord = {0, 1, 2, 0, 2, 4, 2, 5, 4, 5, 8, 4, 8, 7, 4, 7, 6, 4, 6, 3, 4, 3, 0, 4};
  EXPECT_EQ(checkPatch(lowered, noPlane, fan, chord), PatchVerdict::Kept);
  EXPECT_EQ(checkPatch(lowered, plane, fan, chord), PatchVerdict::PlaneEdge);
  // A concave quad A B C D (reflex at C): flipping its diagonal C-A to B-D turns B-C-D over.
  const std::vector<float> quad = {0, 0, 0, 2, 0, 0, 1, 0.5f, 0, 1, 2, 0};
  const std::vector<int> quadPlanes(4, -1);
  EXPECT_EQ(
      checkPatch(quad, quadPlanes, std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}, std::vector<std::uint32_t>{0, 1, 3, 1, 2, 3}),
      PatchVerdict::Turned);
  // Two fans meeting at border vertex 4 only (a pinch: the patch meets 4 from two sides) pass
  // as they came, but not once 4's triangles change: the fan 0-1-2 re-split at 0-2 keeps border
  // and topology, yet could re-pair 4's fans with the rest of the mesh.
  const std::vector<std::uint32_t> twoFans = {0, 1, 4, 1, 2, 4, 8, 7, 4, 7, 6, 4};
  EXPECT_EQ(pinchedVertices(twoFans, 9), (std::vector<char>{0, 0, 0, 0, 1, 0, 0, 0, 0}));
  EXPECT_EQ(checkPatch(lowered, noPlane, twoFans, twoFans), PatchVerdict::Kept);
  const std::vector<std::uint32_t> resplit = {0, 1, 2, 0, 2, 4, 8, 7, 4, 7, 6, 4};
  EXPECT_EQ(checkPatch(lowered, noPlane, twoFans, resplit), PatchVerdict::Pinched);
}

}  // namespace
}  // namespace scansurf::test
