#include <gtest/gtest.h>

#include <vector>

#include "scansurf/surfaces.h"

namespace scansurf {
namespace {

struct HandMesh {
  std::vector<float> positions;
  std::vector<std::uint32_t> triangles;

  std::uint32_t vertex(float x, float y, float z) {
    positions.insert(positions.end(), {x, y, z});
    return static_cast<std::uint32_t>(positions.size() / 3 - 1);
  }
  // Quad a b c d, counter-clockwise seen from its front.
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    triangles.insert(triangles.end(), {a, b, c, a, c, d});
  }
  MeshStats stats() const { return computeMeshStats(positions, triangles); }
};

// Axis-aligned box, faces outward.
void addBox(HandMesh& m, float x0, float y0, float z0, float x1, float y1, float z1) {
  const std::uint32_t v000 = m.vertex(x0, y0, z0), v100 = m.vertex(x1, y0, z0), v010 = m.vertex(x0, y1, z0),
                      v110 = m.vertex(x1, y1, z0), v001 = m.vertex(x0, y0, z1), v101 = m.vertex(x1, y0, z1),
                      v011 = m.vertex(x0, y1, z1), v111 = m.vertex(x1, y1, z1);
  m.quad(v000, v010, v110, v100);  // -z
  m.quad(v001, v101, v111, v011);  // +z
  m.quad(v000, v100, v101, v001);  // -y
  m.quad(v010, v011, v111, v110);  // +y
  m.quad(v000, v001, v011, v010);  // -x
  m.quad(v100, v110, v111, v101);  // +x
}

TEST(MeshStats, Empty) {
  const MeshStats s = computeMeshStats({}, {});
  EXPECT_EQ(s.triangles, 0u);
  EXPECT_EQ(s.components, 0);
  EXPECT_EQ(s.genus, 0);
  EXPECT_EQ(s.volume, 0.0);
}

TEST(MeshStats, UnitCube) {
  HandMesh m;
  addBox(m, 0, 0, 0, 1, 1, 1);
  const MeshStats s = m.stats();
  EXPECT_EQ(s.triangles, 12u);
  EXPECT_EQ(s.vertices, 8u);
  EXPECT_DOUBLE_EQ(s.area, 6.0);
  EXPECT_DOUBLE_EQ(s.volume, 1.0);
  EXPECT_EQ(s.components, 1);
  EXPECT_EQ(s.genus, 0);
  EXPECT_TRUE(s.closed);
  EXPECT_TRUE(s.oriented);
  EXPECT_TRUE(s.manifold);
}

TEST(MeshStats, InvertedCubeHasNegativeVolume) {
  HandMesh m;
  addBox(m, 1, 2, 3, 3, 4, 6);
  for (std::size_t t = 0; t < m.triangles.size(); t += 3) std::swap(m.triangles[t + 1], m.triangles[t + 2]);
  const MeshStats s = m.stats();
  EXPECT_DOUBLE_EQ(s.volume, -12.0);
  EXPECT_DOUBLE_EQ(s.area, 2 * (4 + 6 + 6.0));
  EXPECT_TRUE(s.oriented);
  EXPECT_TRUE(s.manifold);
}

TEST(MeshStats, TwoCubes) {
  HandMesh m;
  addBox(m, 0, 0, 0, 1, 1, 1);
  addBox(m, 5, 0, 0, 7, 1, 1);
  const MeshStats s = m.stats();
  EXPECT_EQ(s.vertices, 16u);
  EXPECT_EQ(s.components, 2);
  EXPECT_EQ(s.genus, 0);
  EXPECT_DOUBLE_EQ(s.volume, 3.0);
  EXPECT_DOUBLE_EQ(s.area, 6.0 + 10.0);
  EXPECT_TRUE(s.closed && s.oriented && s.manifold);
}

TEST(MeshStats, CubesSharingOnlyAVertexAreNotManifold) {
  HandMesh m;
  addBox(m, 0, 0, 0, 1, 1, 1);
  addBox(m, 1, 1, 1, 2, 2, 2);
  // Weld the touching corner: second box's vertex 8 (its 000) onto the first's 7 (111).
  for (auto& v : m.triangles) {
    if (v == 8) v = 7;
  }
  const MeshStats s = m.stats();
  EXPECT_TRUE(s.closed);
  EXPECT_TRUE(s.oriented);
  EXPECT_FALSE(s.manifold);
  EXPECT_EQ(s.components, 2);  // edge-connected, not vertex-connected
  EXPECT_EQ(s.vertices, 15u);
}

// Square ring: outer [0,3]^2, hole [1,2]^2, z in [0,1]. 16 vertices, 32 triangles, genus 1.
HandMesh squareTorus() {
  HandMesh m;
  const float o[4][2] = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
  const float in[4][2] = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  std::uint32_t ob[4], ot[4], ib[4], it[4];
  for (int i = 0; i < 4; ++i) {
    ob[i] = m.vertex(o[i][0], o[i][1], 0);
    ot[i] = m.vertex(o[i][0], o[i][1], 1);
    ib[i] = m.vertex(in[i][0], in[i][1], 0);
    it[i] = m.vertex(in[i][0], in[i][1], 1);
  }
  for (int i = 0; i < 4; ++i) {
    const int n = (i + 1) % 4;
    m.quad(ot[i], ot[n], it[n], it[i]);  // top, +z
    m.quad(ob[i], ib[i], ib[n], ob[n]);  // bottom, -z
    m.quad(ob[i], ob[n], ot[n], ot[i]);  // outer wall, facing away from the centre
    m.quad(ib[i], it[i], it[n], ib[n]);  // inner wall, facing the centre
  }
  return m;
}

TEST(MeshStats, SquareTorus) {
  const MeshStats s = squareTorus().stats();
  EXPECT_EQ(s.triangles, 32u);
  EXPECT_EQ(s.vertices, 16u);
  EXPECT_EQ(s.components, 1);
  EXPECT_EQ(s.genus, 1);
  EXPECT_DOUBLE_EQ(s.volume, 8.0);
  EXPECT_DOUBLE_EQ(s.area, 32.0);
  EXPECT_TRUE(s.closed && s.oriented && s.manifold);
}

TEST(MeshStats, TorusAndCubeGenusSums) {
  HandMesh m = squareTorus();
  addBox(m, 10, 0, 0, 11, 1, 1);
  HandMesh t2 = squareTorus();
  for (std::size_t i = 0; i < t2.positions.size(); i += 3) t2.positions[i] += 20;
  const auto base = static_cast<std::uint32_t>(m.positions.size() / 3);
  m.positions.insert(m.positions.end(), t2.positions.begin(), t2.positions.end());
  for (std::uint32_t v : t2.triangles) m.triangles.push_back(v + base);
  const MeshStats s = m.stats();
  EXPECT_EQ(s.components, 3);
  EXPECT_EQ(s.genus, 2);
  EXPECT_DOUBLE_EQ(s.volume, 17.0);
}

TEST(MeshStats, OpenAndMisoriented) {
  HandMesh m;
  addBox(m, 0, 0, 0, 1, 1, 1);
  HandMesh open = m;
  open.triangles.resize(open.triangles.size() - 3);
  MeshStats s = open.stats();
  EXPECT_FALSE(s.closed);
  EXPECT_FALSE(s.manifold);
  EXPECT_TRUE(s.oriented);  // no directed edge repeats
  EXPECT_EQ(s.components, 1);

  HandMesh flipped = m;
  std::swap(flipped.triangles[1], flipped.triangles[2]);
  s = flipped.stats();
  EXPECT_TRUE(s.closed);
  EXPECT_FALSE(s.oriented);
}

TEST(MeshStats, ThreeTrianglesOnAnEdgeAreNotClosed) {
  HandMesh m;
  addBox(m, 0, 0, 0, 1, 1, 1);
  const std::uint32_t apex = m.vertex(0.5f, -1, 0.5f);
  m.triangles.insert(m.triangles.end(), {0, 1, apex});
  const MeshStats s = m.stats();
  EXPECT_FALSE(s.closed);
  EXPECT_FALSE(s.manifold);
  EXPECT_EQ(s.vertices, 9u);
}

// A triangle that repeats a vertex has the edge (v, v): it counts as an edge and joins the
// triangles that share it, as every other edge does; and a stray trailing index is ignored.
TEST(MeshStats, RepeatedVerticesAndPartialTriangles) {
  HandMesh m;
  for (int i = 0; i < 3; ++i) m.vertex(static_cast<float>(i), static_cast<float>(i * i), 0);
  m.triangles = {0, 0, 1, 0, 0, 2};
  MeshStats s = m.stats();
  EXPECT_FALSE(s.closed);
  EXPECT_FALSE(s.oriented);
  EXPECT_EQ(s.components, 1) << "joined across their shared edge (0, 0)";
  EXPECT_EQ(s.vertices, 3u);
  m.triangles.push_back(1);  // not a whole triangle
  s = m.stats();
  EXPECT_EQ(s.triangles, 2u);
  EXPECT_EQ(s.components, 1);
}

// Features of one shared mesh (two boxes, one of them with a box inside, a feature with no
// surface): in parallel, largest first, the same figures as one at a time, for any thread count.
TEST(MeshStats, FeaturesInParallelGiveEachFeaturesOwnFigures) {
  HandMesh m;
  addBox(m, 0, 0, 0, 4, 4, 4);
  const std::size_t first = m.triangles.size();
  addBox(m, 1, 1, 1, 2, 3, 2);
  const std::size_t second = m.triangles.size();
  addBox(m, 10, 0, 0, 11, 1, 5);
  Surfaces surfaces;
  surfaces.mesh.positions = m.positions;
  const auto part = [&](std::size_t begin, std::size_t end) {
    return std::vector<std::uint32_t>(m.triangles.begin() + static_cast<std::ptrdiff_t>(begin),
                                      m.triangles.begin() + static_cast<std::ptrdiff_t>(end));
  };
  surfaces.features = {{0, part(0, second)}, {1, part(first, second)}, {2, {}}, {3, part(second, m.triangles.size())}};
  for (const int threads : {1, 2, 3, 0}) {
    const std::vector<MeshStats> all = computeFeatureStats(surfaces, threads);
    ASSERT_EQ(all.size(), surfaces.features.size());
    for (std::size_t f = 0; f < all.size(); ++f) {
      const MeshStats one = computeMeshStats(surfaces.mesh.positions, surfaces.features[f].triangles);
      EXPECT_EQ(all[f].triangles, one.triangles) << f;
      EXPECT_EQ(all[f].vertices, one.vertices) << f;
      EXPECT_EQ(all[f].area, one.area) << f;
      EXPECT_EQ(all[f].volume, one.volume) << f;
      EXPECT_EQ(all[f].components, one.components) << f;
      EXPECT_EQ(all[f].genus, one.genus) << f;
      EXPECT_EQ(all[f].closed, one.closed) << f;
    }
    EXPECT_EQ(all[0].components, 2);
    EXPECT_DOUBLE_EQ(all[0].volume, 64 + 2);  // the inner box, faces outward too, adds its own
    EXPECT_EQ(all[2].triangles, 0u);
    EXPECT_DOUBLE_EQ(all[3].volume, 5);
  }
}

}  // namespace
}  // namespace scansurf
