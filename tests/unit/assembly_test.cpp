#include "geometry/extraction/assembly.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "geometry/extraction/cell_cases.h"
#include "geometry/extraction/feature_surfaces.h"
#include "support/surface_checks.h"

namespace scansurf {
namespace {

using Inside = std::function<bool(double, double, double)>;

// An n^3 grid of spacing h centred on the origin; voxel label = 1 + the first feature in
// `priority` (innermost first) whose shape holds the voxel centre; border voxels stay 0.
LabelVolume implicitVolume(int n, double h, const std::vector<Inside>& features, std::vector<int> priority = {}) {
  if (priority.empty())
    for (int f = 0; f < static_cast<int>(features.size()); ++f) priority.push_back(f);
  LabelVolume v;
  v.grid.nx = v.grid.ny = v.grid.nz = n;
  v.grid.originX = v.grid.originY = -(n - 1) * h / 2;
  v.grid.spacingX = v.grid.spacingY = h;
  for (int k = 0; k < n; ++k) v.grid.layerZ.push_back(-(n - 1) * h / 2 + k * h);
  v.labels.assign(v.grid.voxelCount(), kBackground);
  for (int k = 1; k + 1 < n; ++k)
    for (int j = 1; j + 1 < n; ++j)
      for (int i = 1; i + 1 < n; ++i) {
        const double x = v.grid.originX + i * h, y = v.grid.originY + j * h, z = v.grid.layerZ[k];
        for (int f : priority)
          if (features[f](x, y, z)) {
            v.labels[v.grid.index(i, j, k)] = labelOfFeature(f);
            break;
          }
      }
  return v;
}

Inside ball(double cx, double cy, double cz, double r) {
  return [=](double x, double y, double z) { return (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) <= r * r; };
}

MultiLabelMesh meshOf(const LabelVolume& v, int threads = 0) {
  const std::vector<CellCase> cases = classifyCellsReference(v);
  return assembleMesh(v.grid, cases, threads);
}

Nesting flatNesting(int featureCount) {
  Nesting n;
  for (int f = 0; f < featureCount; ++f) n.order.push_back(f);
  n.parent.assign(static_cast<std::size_t>(featureCount), -1);
  return n;
}

MeshStats statsOf(const MultiLabelMesh& mesh, const FeatureSurface& s) { return computeMeshStats(mesh.positions, s.triangles); }

// Every non-empty surface in both conventions: closed, manifold, oriented, positive volume.
void expectWellFormed(const MultiLabelMesh& mesh, int featureCount, const Nesting& nesting) {
  for (SurfaceConvention convention : {SurfaceConvention::Enclosing, SurfaceConvention::Partition}) {
    const auto surfaces = extractFeatureSurfaces(mesh, featureCount, nesting, convention);
    ASSERT_EQ(surfaces.size(), static_cast<std::size_t>(featureCount));
    for (const FeatureSurface& s : surfaces) {
      if (s.triangles.empty()) continue;
      const MeshStats st = statsOf(mesh, s);
      const int c = static_cast<int>(convention);
      EXPECT_TRUE(st.closed) << "feature " << s.feature << " convention " << c;
      EXPECT_TRUE(st.manifold) << "feature " << s.feature << " convention " << c;
      EXPECT_TRUE(st.oriented) << "feature " << s.feature << " convention " << c;
      EXPECT_GT(st.volume, 0) << "feature " << s.feature << " convention " << c;
    }
  }
}

TEST(CaseTable, SingleVoxelIsAnOctahedron) {
  // A lone voxel: every tet around it is a 3+1 split, one flat triangle each.
  LabelVolume v = implicitVolume(3, 1.0, {ball(0, 0, 0, 0.1)});
  const MultiLabelMesh mesh = meshOf(v);
  const MeshStats s = computeMeshStats(mesh.positions, mesh.triangles);
  EXPECT_TRUE(s.closed && s.manifold && s.oriented);
  EXPECT_EQ(s.genus, 0);
  EXPECT_EQ(s.components, 1);
  // Freudenthal: the centre voxel has 14 neighbours along tet edges, so 14 midpoints and
  // 24 tets around it (one triangle each).
  EXPECT_EQ(mesh.vertexCount(), 14u);
  EXPECT_EQ(mesh.triangleCount(), 24u);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    EXPECT_EQ(mesh.labels[2 * t], 0);
    EXPECT_EQ(mesh.labels[2 * t + 1], 1);
  }
  // Normals point from background (a = 0) into the voxel: the mesh's volume is negative.
  EXPECT_LT(s.volume, 0);
  // Every vertex is a half-step midpoint: 1/2 along each axis from the centre, exactly.
  for (float p : mesh.positions) EXPECT_TRUE(p == 0.0f || p == 0.5f || p == -0.5f);
}

TEST(Assembly, SphereVolumeWithinThreePercent) {
  const double r = 10.0;
  const LabelVolume v = implicitVolume(25, 1.0, {ball(0.2, -0.1, 0.3, r)});
  const MultiLabelMesh mesh = meshOf(v);
  const auto surfaces = extractFeatureSurfaces(mesh, 1, flatNesting(1), SurfaceConvention::Enclosing);
  const MeshStats s = statsOf(mesh, surfaces[0]);
  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  std::printf("sphere r=10 at 1 mm: volume %.1f vs %.1f (%.2f%%), area %.1f vs %.1f, %zu triangles\n", s.volume, exact,
              100 * (s.volume - exact) / exact, s.area, 4 * std::numbers::pi * r * r, s.triangles);
  EXPECT_NEAR(s.volume, exact, 0.03 * exact);
  EXPECT_TRUE(s.closed && s.manifold && s.oriented);
  EXPECT_EQ(s.components, 1);
  EXPECT_EQ(s.genus, 0);
}

TEST(Assembly, Torus) {
  const double big = 8, small = 3;
  const Inside torus = [=](double x, double y, double z) {
    const double q = std::sqrt(x * x + y * y) - big;
    return q * q + z * z <= small * small;
  };
  const LabelVolume v = implicitVolume(26, 1.0, {torus});
  const MultiLabelMesh mesh = meshOf(v);
  const auto surfaces = extractFeatureSurfaces(mesh, 1, flatNesting(1), SurfaceConvention::Partition);
  const MeshStats s = statsOf(mesh, surfaces[0]);
  const double exact = 2 * std::numbers::pi * std::numbers::pi * big * small * small;
  std::printf("torus R=8 r=3 at 1 mm: volume %.1f vs %.1f (%.2f%%)\n", s.volume, exact, 100 * (s.volume - exact) / exact);
  EXPECT_TRUE(s.closed && s.manifold && s.oriented);
  EXPECT_EQ(s.components, 1);
  EXPECT_EQ(s.genus, 1);
  EXPECT_NEAR(s.volume, exact, 0.05 * exact);
}

TEST(Assembly, TwoSeparateBalls) {
  const LabelVolume v = implicitVolume(
      24, 1.0, {[](double x, double y, double z) { return ball(-5, 0, 0, 4)(x, y, z) || ball(6, 1, 0, 3.5)(x, y, z); }});
  const MultiLabelMesh mesh = meshOf(v);
  const auto surfaces = extractFeatureSurfaces(mesh, 1, flatNesting(1), SurfaceConvention::Enclosing);
  const MeshStats s = statsOf(mesh, surfaces[0]);
  EXPECT_EQ(s.components, 2);
  EXPECT_EQ(s.genus, 0);
  EXPECT_TRUE(s.closed && s.manifold && s.oriented);
}

TEST(Assembly, NestedSpheres) {
  // Feature 0 (inner ball) inside feature 1 (outer ball).
  const LabelVolume v = implicitVolume(24, 1.0, {ball(0, 0, 0, 4.5), ball(0, 0, 0, 9.5)});
  const MultiLabelMesh mesh = meshOf(v);
  Nesting nesting = flatNesting(2);
  nesting.parent[0] = 1;
  ASSERT_TRUE(isInside(nesting, 0, 1));
  ASSERT_FALSE(isInside(nesting, 1, 0));
  expectWellFormed(mesh, 2, nesting);
  const auto enclosing = extractFeatureSurfaces(mesh, 2, nesting, SurfaceConvention::Enclosing);
  const auto partition = extractFeatureSurfaces(mesh, 2, nesting, SurfaceConvention::Partition);
  const MeshStats inner = statsOf(mesh, partition[0]);
  const MeshStats shell = statsOf(mesh, partition[1]);
  const MeshStats outer = statsOf(mesh, enclosing[1]);
  EXPECT_EQ(inner.components, 1);
  EXPECT_EQ(shell.components, 2);  // outer sphere and the (inward-facing) inner sphere
  EXPECT_EQ(shell.genus, 0);
  EXPECT_EQ(outer.components, 1);
  EXPECT_NEAR(shell.volume + inner.volume, outer.volume, 1e-6 * outer.volume);
  // The inner ball's two conventions agree; the outer's enclosing surface has no label-1 side.
  EXPECT_EQ(enclosing[0].triangles, partition[0].triangles);
  EXPECT_EQ(outer.triangles + inner.triangles, shell.triangles);
}

TEST(Assembly, AbuttingHalfBallsShareInterfaceVertices) {
  const Inside left = [](double x, double y, double z) { return x < 0.5 && ball(0, 0, 0, 8)(x, y, z); };
  const Inside right = [](double x, double y, double z) { return x >= 0.5 && ball(0, 0, 0, 8)(x, y, z); };
  const LabelVolume v = implicitVolume(21, 1.0, {left, right});
  const MultiLabelMesh mesh = meshOf(v);
  expectWellFormed(mesh, 2, flatNesting(2));
  // Vertices are unique by position (dedupe by exact key).
  std::set<std::array<float, 3>> positions;
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i)
    positions.insert({mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]});
  EXPECT_EQ(positions.size(), mesh.vertexCount());
  for (SurfaceConvention convention : {SurfaceConvention::Enclosing, SurfaceConvention::Partition}) {
    const auto surfaces = extractFeatureSurfaces(mesh, 2, flatNesting(2), convention);
    const test::InterfaceUse use = test::interfaceUse(mesh, surfaces[0], surfaces[1], 1, 2);
    EXPECT_EQ(use.unshared, 0u);
    EXPECT_GT(use.triangles, 50u);
    // The interface is a flat disk at x = 0.5 - 1/2 voxel... its vertices lie on x = 0 or 1.
    const MeshStats s0 = statsOf(mesh, surfaces[0]), s1 = statsOf(mesh, surfaces[1]);
    EXPECT_EQ(s0.components, 1);
    EXPECT_EQ(s1.components, 1);
  }
}

TEST(Assembly, ThreeLabelsMeetAlongALine) {
  // Three wedges around the z axis inside a ball.
  std::vector<Inside> wedges;
  for (int w = 0; w < 3; ++w)
    wedges.push_back([w](double x, double y, double z) {
      double angle = std::atan2(y - 0.3, x - 0.2) + std::numbers::pi;  // [0, 2pi]
      const int sector = std::min(2, static_cast<int>(angle / (2 * std::numbers::pi / 3)));
      return sector == w && ball(0, 0, 0, 8)(x, y, z);
    });
  const LabelVolume v = implicitVolume(20, 1.0, wedges);
  const MultiLabelMesh mesh = meshOf(v);
  expectWellFormed(mesh, 3, flatNesting(3));
  std::set<std::pair<Label, Label>> pairs;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) pairs.insert({mesh.labels[2 * t], mesh.labels[2 * t + 1]});
  EXPECT_EQ(pairs, (std::set<std::pair<Label, Label>>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}));
}

TEST(Assembly, FourLabelsMeetAtAPoint) {
  // Four regions of a ball: x<c & y<c, x>=c & y<c, and z splits the rest in two.
  auto region = [](int w) -> Inside {
    return [w](double x, double y, double z) {
      int r;
      if (y < 0.3)
        r = x < 0.1 ? 0 : 1;
      else
        r = z < -0.2 ? 2 : 3;
      return r == w && ball(0, 0, 0, 7)(x, y, z);
    };
  };
  const LabelVolume v = implicitVolume(18, 1.0, {region(0), region(1), region(2), region(3)});
  const MultiLabelMesh mesh = meshOf(v);
  expectWellFormed(mesh, 4, flatNesting(4));
  // Some tetrahedra hold four labels: a tet centroid shared by triangles of 6 label pairs.
  Nesting everything = flatNesting(4);
  for (int f = 1; f < 4; ++f) everything.parent[f] = 0;
  const auto all = extractFeatureSurfaces(mesh, 4, everything, SurfaceConvention::Enclosing);
  const auto partition = extractFeatureSurfaces(mesh, 4, everything, SurfaceConvention::Partition);
  double sum = 0;
  for (const auto& s : partition) sum += statsOf(mesh, s).volume;
  EXPECT_NEAR(sum, statsOf(mesh, all[0]).volume, 1e-6 * sum);
}

// The boundary of the union of all non-background labels, outward.
std::vector<std::uint32_t> unionSurface(const MultiLabelMesh& mesh) {
  std::vector<std::uint32_t> out;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    if (mesh.labels[2 * t] != kBackground) continue;
    out.insert(out.end(), {mesh.triangles[3 * t], mesh.triangles[3 * t + 2], mesh.triangles[3 * t + 1]});
  }
  return out;
}

LabelVolume randomVolume(unsigned seed, int n, int labels) {
  LabelVolume v = implicitVolume(n, 1.0, {});
  std::mt19937 rng(seed);
  for (int k = 1; k + 1 < n; ++k)
    for (int j = 1; j + 1 < n; ++j)
      for (int i = 1; i + 1 < n; ++i) v.labels[v.grid.index(i, j, k)] = static_cast<Label>(rng() % (labels + 1));
  return v;
}

TEST(Assembly, RandomVolumesAreWellFormed) {
  for (unsigned seed = 0; seed < 24; ++seed) {
    const int labels = 2 + static_cast<int>(seed % 4);  // 2..5 features plus background
    LabelVolume v = randomVolume(seed, 12, labels);
    // Uneven layers: positions change, topology must not.
    for (int k = 0; k < v.grid.nz; ++k) v.grid.layerZ[k] = 0.7 * k + 0.05 * k * k;
    const MultiLabelMesh mesh = meshOf(v);
    SCOPED_TRACE(seed);
    // Random containment forest: feature f inside a random earlier-indexed... later feature.
    Nesting nesting = flatNesting(labels);
    std::mt19937 rng(seed * 7 + 1);
    for (int f = 0; f + 1 < labels; ++f)
      if (rng() % 2) nesting.parent[f] = f + 1 + static_cast<int>(rng() % (labels - f - 1));
    expectWellFormed(mesh, labels, nesting);

    // Non-degenerate triangles with a < b.
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      ASSERT_LT(mesh.labels[2 * t], mesh.labels[2 * t + 1]);
      const std::uint32_t* tri = &mesh.triangles[3 * t];
      ASSERT_TRUE(tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2]);
      double p[3][3];
      for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) p[c][a] = mesh.positions[3 * tri[c] + a];
      const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
      const double w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
      const double cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2], cz = u[0] * w[1] - u[1] * w[0];
      ASSERT_GT(std::sqrt(cx * cx + cy * cy + cz * cz), 1e-4);
    }

    // Partition volumes sum to the volume of the union of all labelled regions.
    const auto partition = extractFeatureSurfaces(mesh, labels, nesting, SurfaceConvention::Partition);
    double sum = 0;
    for (const auto& s : partition) sum += statsOf(mesh, s).volume;
    const MeshStats all = computeMeshStats(mesh.positions, unionSurface(mesh));
    EXPECT_TRUE(all.closed && all.manifold && all.oriented);
    EXPECT_NEAR(sum, all.volume, 1e-6 * all.volume);
    // The whole multi-label mesh: each edge is shared by an even number of triangles.
  }
}

TEST(Assembly, IdenticalForAnyThreadCount) {
  const LabelVolume v = randomVolume(99, 16, 4);
  const std::vector<CellCase> cases = classifyCellsReference(v);
  const MultiLabelMesh one = assembleMesh(v.grid, cases, 1);
  ASSERT_GT(one.triangleCount(), 1000u);
  for (int threads : {2, 3, 5}) {
    const MultiLabelMesh other = assembleMesh(v.grid, cases, threads);
    EXPECT_EQ(other.positions, one.positions) << threads;
    EXPECT_EQ(other.triangles, one.triangles) << threads;
    EXPECT_EQ(other.labels, one.labels) << threads;
  }
}

// Two copies of a volume's cells in one block of a larger grid, the second `far` cells away
// in x, y and z: both copies must come out as the volume alone does, keys, corners and labels.
void expectTwoCopiesIndexAsOne(const LabelVolume& v, const Grid& large, const std::array<std::uint32_t, 3>& far,
                               std::size_t leastCorners) {
  const std::vector<CellCase> cases = classifyCellsReference(v);
  const MultiLabelMesh alone = assembleMesh(v.grid, cases, 2);
  ASSERT_GE(3 * alone.triangleCount(), leastCorners);
  const auto cellOf = [](const Grid& g, std::uint64_t i, std::uint64_t j, std::uint64_t k) {
    return i + static_cast<std::uint64_t>(g.nx - 1) * (j + static_cast<std::uint64_t>(g.ny - 1) * k);
  };
  std::vector<CellCase> twice;
  for (int copy = 0; copy < 2; ++copy)
    for (CellCase c : cases) {
      const std::uint64_t i = c.cell % (v.grid.nx - 1), j = c.cell / (v.grid.nx - 1) % (v.grid.ny - 1),
                          k = c.cell / (v.grid.nx - 1) / (v.grid.ny - 1);
      c.cell = static_cast<std::uint32_t>(copy == 0 ? cellOf(large, i, j, k) : cellOf(large, i + far[0], j + far[1], k + far[2]));
      twice.push_back(c);
    }
  const MultiLabelMesh both = assembleMesh(large, twice, 2);
  const std::size_t vertices = alone.vertexCount(), triangles = alone.triangleCount();
  ASSERT_EQ(both.vertexCount(), 2 * vertices);
  ASSERT_EQ(both.triangleCount(), 2 * triangles);
  const std::uint64_t shift = packVertexKey(12 * std::uint64_t{far[0]}, 12 * std::uint64_t{far[1]}, 12 * std::uint64_t{far[2]});
  for (std::size_t i = 0; i < vertices; ++i) {
    ASSERT_EQ(both.keys[i], alone.keys[i]) << i;
    ASSERT_EQ(both.keys[vertices + i], alone.keys[i] + shift) << i;
  }
  for (std::size_t i = 0; i < 3 * triangles; ++i) {
    ASSERT_EQ(both.triangles[i], alone.triangles[i]) << i;
    ASSERT_EQ(both.triangles[3 * triangles + i], alone.triangles[i] + vertices) << i;
  }
  const auto half = static_cast<std::ptrdiff_t>(alone.labels.size());
  EXPECT_TRUE(std::equal(alone.labels.begin(), alone.labels.end(), both.labels.begin()));
  EXPECT_TRUE(std::equal(alone.labels.begin(), alone.labels.end(), both.labels.begin() + half));
}

Grid largeGrid(const Grid& small, int nx, int ny, int nz) {
  Grid g = small;
  g.nx = nx, g.ny = ny, g.nz = nz;
  while (g.layerZ.size() < static_cast<std::size_t>(nz)) g.layerZ.push_back(g.layerZ.back() + 1.0);
  return g;
}

// Assembly sorts a block's keys relative to its least corner, by radix, as many passes as
// their range needs: here four (2 x 10^10 values, two copies 100 000 layers apart).
TEST(Assembly, KeysSpanningManyLayersIndexTheSame) {
  const LabelVolume v = randomVolume(7, 16, 3);
  expectTwoCopiesIndexAsOne(v, largeGrid(v.grid, 16, 16, 100016), {0, 0, 100000}, 1000);
}

// A block whose relative keys and corner numbers do not fit one 64-bit word (2^42.7 values
// over a grid of 2^32 cells, over 2^22 corners) is sorted the slower general way, to the same end.
TEST(Assembly, KeysTooWideForOneWordIndexTheSame) {
  const LabelVolume v = randomVolume(11, 32, 6);
  expectTwoCopiesIndexAsOne(v, largeGrid(v.grid, 2049, 2049, 1025), {2048 - 31, 2048 - 31, 1024 - 31}, std::size_t{1} << 21);
}

TEST(Assembly, PositionsFollowUnevenLayers) {
  LabelVolume v = implicitVolume(3, 1.0, {ball(0, 0, 0, 0.1)});
  v.grid.originX = 10;
  v.grid.originY = 20;
  v.grid.spacingX = 2;
  v.grid.spacingY = 4;
  v.grid.layerZ = {0, 1, 5};
  const MultiLabelMesh mesh = meshOf(v);
  std::set<float> xs, ys, zs;
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    xs.insert(mesh.positions[3 * i]);
    ys.insert(mesh.positions[3 * i + 1]);
    zs.insert(mesh.positions[3 * i + 2]);
  }
  EXPECT_EQ(xs, (std::set<float>{11, 12, 13}));
  EXPECT_EQ(ys, (std::set<float>{22, 24, 26}));
  EXPECT_EQ(zs, (std::set<float>{0.5f, 1, 3}));
  // Vertices in key order: z-major.
  for (std::size_t i = 1; i < mesh.vertexCount(); ++i) EXPECT_LE(mesh.positions[3 * i - 1], mesh.positions[3 * i + 2]);
}

TEST(Assembly, EmptyInput) {
  const LabelVolume v = implicitVolume(4, 1.0, {});
  const MultiLabelMesh mesh = meshOf(v);
  EXPECT_EQ(mesh.vertexCount(), 0u);
  EXPECT_EQ(mesh.triangleCount(), 0u);
}

}  // namespace
}  // namespace scansurf
