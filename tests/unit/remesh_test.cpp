// Remeshing of the separating-surface network (issue 11), on the CPU pipeline:
// makeGrid -> referenceScanConvert -> classifyCellsReference -> assembleMesh -> smoothMesh ->
// remeshMesh. Every shape the smoothing tests use, checked exactly after remeshing.
#include "geometry/remesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>
#include <vector>

#include "geometry/feature_surfaces.h"
#include "geometry/smoothing.h"
#include "support/intersections.h"
#include "support/shapes.h"
#include "support/surface_checks.h"

namespace scansurf::test {
namespace {

RemeshOptions remeshOn(double edgeLength = 0) {
  RemeshOptions o;
  o.enabled = true;
  o.edgeLength = edgeLength;
  return o;
}

void smooth(Built& b, int threads = 0) {
  SmoothingOptions o;
  o.enabled = true;
  smoothMesh(b.mesh, b.grid, &b.set, o, threads);
}

RemeshReport remesh(Built& b, const RemeshOptions& options = remeshOn()) {
  const RemeshReport r = remeshMesh(b.mesh, b.grid, &b.set, b.nesting, options);
  refreshFeatures(b);
  return r;
}

// Per feature surface of one convention: its statistics.
std::vector<MeshStats> surfaceStats(const Built& b, SurfaceConvention convention) {
  std::vector<MeshStats> out;
  for (const FeatureSurface& s : extractFeatureSurfaces(b.mesh, static_cast<int>(b.set.features.size()), b.nesting, convention))
    out.push_back(computeMeshStats(b.mesh.positions, s.triangles));
  return out;
}

// Area of the triangles of each label pair.
std::map<std::pair<Label, Label>, double> areaByPair(const MultiLabelMesh& m) {
  std::map<std::pair<Label, Label>, double> out;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const float* p[3] = {&m.positions[3 * m.triangles[3 * t]], &m.positions[3 * m.triangles[3 * t + 1]],
                         &m.positions[3 * m.triangles[3 * t + 2]]};
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) u[k] = p[1][k] - p[0][k], v[k] = p[2][k] - p[0][k];
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    out[{m.labels[2 * t], m.labels[2 * t + 1]}] += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return out;
}

// Every vertex of a triangle between two abutting features (neither inside the other) lies on
// both features' enclosing surfaces.
void expectSharedInterfaces(const Built& b) {
  std::vector<std::set<std::uint32_t>> vertices;
  for (const FeatureSurface& s : b.features) vertices.emplace_back(s.triangles.begin(), s.triangles.end());
  std::size_t shared = 0;
  for (std::size_t t = 0; t < b.mesh.triangleCount(); ++t) {
    const int fa = featureOfLabel(b.mesh.labels[2 * t]), fb = featureOfLabel(b.mesh.labels[2 * t + 1]);
    if (fa < 0 || fb < 0 || isInside(b.nesting, fa, fb) || isInside(b.nesting, fb, fa)) continue;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = b.mesh.triangles[3 * t + c];
      EXPECT_TRUE(vertices[static_cast<std::size_t>(fa)].count(v) && vertices[static_cast<std::size_t>(fb)].count(v));
      ++shared;
    }
  }
  std::printf("[ figure   ] %-14s %zu interface vertex uses shared\n", b.set.source.c_str(), shared);
}

// Smooths and remeshes `set`, checking everything remeshing promises against the smoothed mesh.
Built checkRemesh(const ContourSet& set, double voxel, const RemeshOptions& options = remeshOn()) {
  Built b = buildCpu(set, voxel);
  smooth(b);
  const std::vector<MeshStats> enclosing = surfaceStats(b, SurfaceConvention::Enclosing);
  const std::vector<MeshStats> partition = surfaceStats(b, SurfaceConvention::Partition);
  const auto areas = areaByPair(b.mesh);
  const RemeshReport r = remesh(b, options);
  EXPECT_TRUE(r.ran);
  EXPECT_TRUE(b.mesh.keys.empty());
  for (const auto& [convention, before] : {std::pair{SurfaceConvention::Enclosing, enclosing}, std::pair{SurfaceConvention::Partition, partition}}) {
    const std::vector<MeshStats> after = surfaceStats(b, convention);
    for (std::size_t f = 0; f < after.size(); ++f) {
      const MeshStats &s = after[f], &o = before[f];
      const char* name = convention == SurfaceConvention::Enclosing ? "enclosing" : "partition";
      EXPECT_EQ(s.triangles == 0, o.triangles == 0) << set.source << " " << name << " feature " << f;
      if (o.triangles == 0) continue;
      EXPECT_TRUE(s.closed && s.manifold && s.oriented) << set.source << " " << name << " feature " << f;
      EXPECT_EQ(s.genus, o.genus) << set.source << " " << name << " feature " << f;
      EXPECT_EQ(s.components, o.components) << set.source << " " << name << " feature " << f;
      EXPECT_NEAR(s.volume, o.volume, 0.02 * std::abs(o.volume)) << set.source << " " << name << " feature " << f;
    }
  }
  // Labels preserved: the same label pairs, each separating about the same area.
  const auto areasAfter = areaByPair(b.mesh);
  EXPECT_EQ(areasAfter.size(), areas.size());
  for (const auto& [pair, area] : areas) {
    EXPECT_TRUE(areasAfter.count(pair)) << set.source << " lost the pair " << pair.first << "/" << pair.second;
    if (areasAfter.count(pair)) {
      EXPECT_NEAR(areasAfter.at(pair), area, 0.03 * area) << set.source << " pair " << pair.first << "/" << pair.second;
    }
  }
  const IntersectionReport x = findCrossings(b.mesh.positions, b.mesh.triangles);
  EXPECT_EQ(x.crossings, 0u) << set.source;
  EXPECT_EQ(x.degenerate, 0u) << set.source;
  EXPECT_GT(x.pairsTested, b.mesh.triangleCount()) << "the broad phase must pair up neighbours";
  EXPECT_LE(r.maxDistance, 0.1 * std::min(b.grid.spacingX, b.grid.spacingY) + 1e-6) << set.source;
  const Angles a = minAngles(b.mesh);
  EXPECT_NEAR(a.min, r.anglesAfter.min, 1e-4);  // float vs double acos
  std::printf("[ figure   ] %-14s triangles %7zu -> %7zu, min angle %5.1f -> %5.1f, 5%% %5.1f -> %5.1f, mean %5.1f -> %5.1f, "
              "max distance %.4f, %zu pairs tested exactly, %zu crossing\n",
              set.source.c_str(), r.trianglesBefore, r.trianglesAfter, r.anglesBefore.min, r.anglesAfter.min, r.anglesBefore.p5,
              r.anglesAfter.p5, r.anglesBefore.mean, r.anglesAfter.mean, r.maxDistance, x.pairsTested, x.crossings);
  std::printf("[ figure   ] %-14s %zu splits, %zu collapses, %zu flips, %zu moves, %zu refused\n", set.source.c_str(), r.splits,
              r.collapses, r.flips, r.moves, r.rejected);
  return b;
}

// ---------------------------------------------------------------- soundness on every shape

TEST(Remesh, NestedSpheres) { checkRemesh(nestedSpheresContours(), 1.0); }
TEST(Remesh, AbuttingHalvesShareEveryInterfaceVertex) {
  const Built b = checkRemesh(abuttingContours(10, 6, 2.5), 0.5);
  expectSharedInterfaces(b);
}
TEST(Remesh, BranchingVessel) { checkRemesh(yBranchContours(), 0.5); }
TEST(Remesh, Phantom) {
  const Built b = checkRemesh(phantomContours(), 1.0);
  expectSharedInterfaces(b);
}

}  // namespace
}  // namespace scansurf::test
