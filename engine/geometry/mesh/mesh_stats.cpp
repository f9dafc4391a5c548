// Topological and metric statistics of a triangle mesh: edge use counts for closedness and
// orientation, vertex link connectivity for manifoldness, Euler characteristic per
// edge-connected component for genus, and the divergence theorem for volume. One walk over
// the vertices and their corners (no sort of the whole mesh's edges): linear in the surface.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/parallel.h"
#include "geometry/mesh/mesh_topology.h"
#include "scansurf/surfaces.h"

namespace scansurf {

namespace {

// singleFan for a link of at most kSmallLink edges (almost every vertex): the same union-find
// over its vertices, on the stack, each vertex found by a linear scan.
constexpr std::size_t kSmallLink = 32;

bool singleSmallFan(std::span<const std::array<std::uint32_t, 2>> link) {
  std::array<std::uint32_t, 2 * kSmallLink> ids, parent;
  std::size_t count = 0;
  const auto local = [&](std::uint32_t v) {
    for (std::size_t i = 0; i < count; ++i)
      if (ids[i] == v) return i;
    ids[count] = v, parent[count] = static_cast<std::uint32_t>(count);
    return count++;
  };
  const auto root = [&](std::size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::size_t components = 0;
  for (const auto& e : link) {
    const std::size_t before = count, a = root(local(e[0])), b = root(local(e[1]));
    components += count - before;
    if (a != b) parent[a] = static_cast<std::uint32_t>(b), --components;
  }
  return components <= 1;  // an empty link counts as one fan, as below
}

}  // namespace

// True when the triangles around v (given as the opposite edges of v's link) form one fan.
bool singleFan(std::span<const std::array<std::uint32_t, 2>> link, std::vector<std::uint32_t>& scratch) {
  if (link.size() <= kSmallLink) return singleSmallFan(link);
  scratch.clear();
  for (const auto& e : link) {
    scratch.push_back(e[0]);
    scratch.push_back(e[1]);
  }
  std::sort(scratch.begin(), scratch.end());
  scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
  UnionFind uf(scratch.size());
  auto local = [&](std::uint32_t v) {
    return static_cast<std::uint32_t>(std::lower_bound(scratch.begin(), scratch.end(), v) - scratch.begin());
  };
  for (const auto& e : link) uf.unite(local(e[0]), local(e[1]));
  for (std::uint32_t i = 0; i < scratch.size(); ++i)
    if (uf.find(i) != 0) return false;
  return true;
}

namespace {

constexpr std::uint32_t kNone = ~std::uint32_t{0};

// Area and enclosed volume (signed tetrahedra against the origin: p0 . (p1 x p2) / 6).
void measure(std::span<const float> positions, std::span<const std::uint32_t> triangles, MeshStats& stats) {
  double area = 0, volume = 0;
  for (std::size_t f = 0; f < triangles.size() / 3; ++f) {
    std::array<std::array<double, 3>, 3> p{};
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a) p[c][a] = positions[3 * triangles[3 * f + c] + a];
    const std::array<double, 3> u = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const std::array<double, 3> v = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const std::array<double, 3> cr = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    area += 0.5 * std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    volume += (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
               p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])) /
              6.0;
  }
  stats.area = area;
  stats.volume = volume;
}

// The surface's own vertices, numbered densely in order of first use (through a table as long
// as the highest index: one clearing pass, no hashing), and each one's corners
// (3 * triangle + corner) as compressed rows: everything below walks vertex by vertex and sorts
// only the few edges around one vertex.
struct VertexCorners {
  std::vector<std::uint32_t> vertices;  // global index of each local vertex
  std::vector<std::uint32_t> start;     // corners of local vertex v: corners[start[v] .. start[v + 1])
  std::vector<std::uint32_t> corners;
};

VertexCorners cornersByVertex(std::span<const std::uint32_t> triangles) {
  const std::uint32_t most = triangles.empty() ? 0 : *std::max_element(triangles.begin(), triangles.end());
  std::vector<std::uint32_t> local(triangles.empty() ? 0 : std::size_t{most} + 1, kNone);
  VertexCorners vc;
  for (const std::uint32_t v : triangles)
    if (local[v] == kNone) local[v] = static_cast<std::uint32_t>(vc.vertices.size()), vc.vertices.push_back(v);
  vc.start.assign(vc.vertices.size() + 1, 0);
  for (const std::uint32_t v : triangles) ++vc.start[local[v] + 1];
  std::partial_sum(vc.start.begin(), vc.start.end(), vc.start.begin());
  vc.corners.resize(triangles.size());
  std::vector<std::uint32_t> fill(vc.start.begin(), vc.start.end() - 1);
  for (std::size_t c = 0; c < triangles.size(); ++c) vc.corners[fill[local[triangles[c]]]++] = static_cast<std::uint32_t>(c);
  return vc;
}

// One use of the edge from a vertex to `other` (a greater vertex index) by `triangle`;
// outward when the triangle's winding runs from the vertex to `other`.
struct EdgeUse {
  std::uint32_t other, triangle;
  bool outward;
  bool operator<(const EdgeUse& o) const {
    if (other != o.other) return other < o.other;
    if (outward != o.outward) return outward < o.outward;
    return triangle < o.triangle;
  }
};

// What the edges say: closed when every undirected edge has two uses, oriented when no
// directed edge repeats (for a closed mesh: each edge once in each direction); the triangles'
// components (joined across edges), one triangle per undirected edge, and whether every
// vertex's link (the edges opposite it) is one connected fan.
struct EdgeCensus {
  bool closed = true, oriented = true, fans = true;
  UnionFind components;
  std::vector<std::uint32_t> edgeTriangle;
};

// The edges of vertex v to greater vertices, each edge counted at its smaller end.
void censusAtVertex(std::span<const std::uint32_t> triangles, std::span<const std::uint32_t> corners, std::uint32_t v,
                    EdgeCensus& census, std::vector<EdgeUse>& uses, std::vector<std::array<std::uint32_t, 2>>& link,
                    std::vector<std::uint32_t>& scratch) {
  uses.clear();
  link.clear();
  for (const std::uint32_t c : corners) {
    const std::uint32_t f = c / 3, next = triangles[3 * f + (c + 1) % 3], prev = triangles[3 * f + (c + 2) % 3];
    if (next == v || prev == v) census.closed = census.oriented = false;  // a degenerate triangle
    if (next >= v) uses.push_back({next, f, true});  // a repeated vertex's edge (v, v) counts once, as any edge
    if (prev > v) uses.push_back({prev, f, false});
    link.push_back({next, prev});
  }
  std::sort(uses.begin(), uses.end());
  for (std::size_t begin = 0; begin < uses.size();) {
    std::size_t end = begin + 1;
    while (end < uses.size() && uses[end].other == uses[begin].other) ++end;
    if (end - begin != 2) census.closed = false;
    for (std::size_t i = begin + 1; i < end; ++i) {
      if (uses[i].outward == uses[i - 1].outward) census.oriented = false;
      census.components.unite(uses[begin].triangle, uses[i].triangle);
    }
    census.edgeTriangle.push_back(uses[begin].triangle);
    begin = end;
  }
  if (census.fans && !singleFan(link, scratch)) census.fans = false;
}

EdgeCensus censusOfEdges(std::span<const std::uint32_t> triangles, const VertexCorners& vc) {
  EdgeCensus census{true, true, true, UnionFind(triangles.size() / 3), {}};
  census.edgeTriangle.reserve(triangles.size() / 2 + 1);
  std::vector<EdgeUse> uses;
  std::vector<std::array<std::uint32_t, 2>> link;
  std::vector<std::uint32_t> scratch;
  for (std::size_t v = 0; v < vc.vertices.size(); ++v) {
    const std::span<const std::uint32_t> corners(vc.corners.data() + vc.start[v], vc.start[v + 1] - vc.start[v]);
    censusAtVertex(triangles, corners, vc.vertices[v], census, uses, link, scratch);
  }
  return census;
}

// Components and genus from the Euler characteristic of each component (V counts
// (component, vertex) pairs: a vertex where two components touch counts in both).
void countTopology(std::span<const std::uint32_t> triangles, const VertexCorners& vc, EdgeCensus& census, MeshStats& stats) {
  const std::size_t t = triangles.size() / 3;
  std::vector<std::uint32_t> componentOf(t, 0);
  std::vector<int> index(t, -1);
  int componentCount = 0;
  for (std::size_t f = 0; f < t; ++f) {
    const std::uint32_t root = census.components.find(static_cast<std::uint32_t>(f));
    if (index[root] < 0) index[root] = componentCount++;
    componentOf[f] = static_cast<std::uint32_t>(index[root]);
  }
  std::vector<long long> chi(static_cast<std::size_t>(componentCount), 0);
  for (std::size_t f = 0; f < t; ++f) chi[componentOf[f]] += 1;
  for (std::uint32_t f : census.edgeTriangle) chi[componentOf[f]] -= 1;
  std::vector<std::uint32_t> around;
  for (std::size_t v = 0; v < vc.vertices.size(); ++v) {
    around.clear();
    for (std::uint32_t i = vc.start[v]; i < vc.start[v + 1]; ++i) around.push_back(componentOf[vc.corners[i] / 3]);
    std::sort(around.begin(), around.end());
    for (std::size_t i = 0; i < around.size(); ++i)
      if (i == 0 || around[i] != around[i - 1]) chi[around[i]] += 1;
  }
  stats.components = componentCount;
  long long genus = 0;
  for (long long c : chi) genus += (2 - c) / 2;
  stats.genus = static_cast<int>(genus);
}

}  // namespace

MeshStats computeMeshStats(std::span<const float> positions, std::span<const std::uint32_t> triangles) {
  triangles = triangles.first(3 * (triangles.size() / 3));  // whole triangles only
  MeshStats stats;
  stats.triangles = triangles.size() / 3;
  measure(positions, triangles, stats);
  const VertexCorners vc = cornersByVertex(triangles);
  EdgeCensus census = censusOfEdges(triangles, vc);
  countTopology(triangles, vc, census, stats);
  const std::size_t known = positions.size() / 3;
  stats.vertices =
      static_cast<std::size_t>(std::count_if(vc.vertices.begin(), vc.vertices.end(), [&](std::uint32_t v) { return v < known; }));
  stats.closed = census.closed;
  stats.oriented = census.oriented;
  stats.manifold = census.closed && census.fans;
  return stats;
}

std::vector<MeshStats> computeFeatureStats(const Surfaces& surfaces, int threads) {
  const std::vector<FeatureSurface>& features = surfaces.features;
  std::vector<std::size_t> order(features.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  // Largest first, so that the body (most of the triangles) does not start last.
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return features[a].triangles.size() > features[b].triangles.size(); });
  std::vector<MeshStats> out(features.size());
  std::atomic<std::size_t> next{0};
  const int workers = chunkCount(features.size(), threads);
  parallelChunks(static_cast<std::size_t>(workers), workers, [&](int, std::size_t, std::size_t) {
    for (std::size_t i = next++; i < order.size(); i = next++)
      out[order[i]] = computeMeshStats(surfaces.mesh.positions, features[order[i]].triangles);
  });
  return out;
}

}  // namespace scansurf
