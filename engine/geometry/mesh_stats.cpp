// Topological and metric statistics of a triangle mesh: edge use counts for closedness and
// orientation, vertex link connectivity for manifoldness, Euler characteristic per
// edge-connected component for genus, and the divergence theorem for volume.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "scansurf/surfaces.h"

namespace scansurf {
namespace {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::uint32_t{0}); }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

struct HalfEdge {
  std::uint64_t key;  // min << 32 | max
  std::uint32_t triangle;
  bool forward;  // min -> max in the triangle's winding
  bool operator<(const HalfEdge& o) const {
    if (key != o.key) return key < o.key;
    if (forward != o.forward) return forward < o.forward;
    return triangle < o.triangle;
  }
};

// True when the triangles around v (given as the opposite edges of v's link) form one fan.
bool singleFan(std::span<const std::array<std::uint32_t, 2>> link, std::vector<std::uint32_t>& scratch) {
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

// What the edges say: closed when every undirected edge has two uses, oriented when no
// directed edge repeats (for a closed mesh: each edge once in each direction); the triangles'
// components (joined across edges) and one triangle per undirected edge.
struct EdgeCensus {
  bool closed = true, oriented = true;
  UnionFind components;
  std::vector<std::uint32_t> edgeTriangle;
};

EdgeCensus censusOfEdges(std::span<const std::uint32_t> triangles) {
  const std::size_t t = triangles.size() / 3;
  std::vector<HalfEdge> edges;
  edges.reserve(3 * t);
  bool degenerate = false;
  for (std::size_t f = 0; f < t; ++f) {
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = triangles[3 * f + c], b = triangles[3 * f + (c + 1) % 3];
      if (a == b) degenerate = true;
      const std::uint64_t lo = std::min(a, b), hi = std::max(a, b);
      edges.push_back({lo << 32 | hi, static_cast<std::uint32_t>(f), a < b});
    }
  }
  std::sort(edges.begin(), edges.end());
  EdgeCensus census{!degenerate, !degenerate, UnionFind(t), {}};
  std::size_t begin = 0;
  while (begin < edges.size()) {
    std::size_t end = begin + 1;
    while (end < edges.size() && edges[end].key == edges[begin].key) ++end;
    if (end - begin != 2) census.closed = false;
    for (std::size_t i = begin + 1; i < end; ++i) {
      if (edges[i].forward == edges[i - 1].forward) census.oriented = false;
      census.components.unite(edges[begin].triangle, edges[i].triangle);
    }
    census.edgeTriangle.push_back(edges[begin].triangle);
    begin = end;
  }
  return census;
}

// Components and genus from the Euler characteristic of each component (V counts
// (component, vertex) pairs).
void countTopology(std::span<const std::uint32_t> triangles, EdgeCensus& census, MeshStats& stats) {
  const std::size_t t = triangles.size() / 3;
  std::vector<std::uint32_t> componentOf(t, 0);
  int componentCount = 0;
  std::vector<int> index(t, -1);
  for (std::size_t f = 0; f < t; ++f) {
    const std::uint32_t root = census.components.find(static_cast<std::uint32_t>(f));
    if (index[root] < 0) index[root] = componentCount++;
    componentOf[f] = static_cast<std::uint32_t>(index[root]);
  }
  std::vector<long long> chi(static_cast<std::size_t>(componentCount), 0);
  for (std::size_t f = 0; f < t; ++f) chi[componentOf[f]] += 1;
  for (std::uint32_t f : census.edgeTriangle) chi[componentOf[f]] -= 1;
  std::vector<std::uint64_t> componentVertices;
  componentVertices.reserve(3 * t);
  for (std::size_t f = 0; f < t; ++f)
    for (int c = 0; c < 3; ++c) componentVertices.push_back(std::uint64_t{componentOf[f]} << 32 | triangles[3 * f + c]);
  std::sort(componentVertices.begin(), componentVertices.end());
  componentVertices.erase(std::unique(componentVertices.begin(), componentVertices.end()), componentVertices.end());
  for (std::uint64_t cv : componentVertices) chi[cv >> 32] += 1;
  stats.components = componentCount;
  long long genus = 0;
  for (long long c : chi) genus += (2 - c) / 2;
  stats.genus = static_cast<int>(genus);
}

// Every vertex's link (the edges opposite it) is one connected fan. `vertices`: the surface's
// own, sorted, so that this costs what the surface costs, not the whole shared mesh.
bool everyLinkOneFan(std::span<const std::uint32_t> triangles, const std::vector<std::uint32_t>& vertices) {
  auto local = [&](std::uint32_t v) {
    return static_cast<std::size_t>(std::lower_bound(vertices.begin(), vertices.end(), v) - vertices.begin());
  };
  const std::size_t t = triangles.size() / 3, m = vertices.size();
  std::vector<std::uint32_t> start(m + 1, 0);
  for (std::uint32_t v : triangles) ++start[local(v) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::array<std::uint32_t, 2>> link(3 * t);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t f = 0; f < t; ++f)
    for (int c = 0; c < 3; ++c)
      link[fill[local(triangles[3 * f + c])]++] = {triangles[3 * f + (c + 1) % 3], triangles[3 * f + (c + 2) % 3]};
  std::vector<std::uint32_t> scratch;
  for (std::size_t v = 0; v < m; ++v)
    if (start[v] != start[v + 1] && !singleFan(std::span(link).subspan(start[v], start[v + 1] - start[v]), scratch)) return false;
  return true;
}

}  // namespace

MeshStats computeMeshStats(std::span<const float> positions, std::span<const std::uint32_t> triangles) {
  MeshStats stats;
  stats.triangles = triangles.size() / 3;
  measure(positions, triangles, stats);
  EdgeCensus census = censusOfEdges(triangles);
  countTopology(triangles, census, stats);
  std::vector<std::uint32_t> vertices(triangles.begin(), triangles.end());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  stats.vertices =
      static_cast<std::size_t>(std::lower_bound(vertices.begin(), vertices.end(), positions.size() / 3) - vertices.begin());
  stats.closed = census.closed;
  stats.oriented = census.oriented;
  stats.manifold = census.closed && everyLinkOneFan(triangles, vertices);
  return stats;
}

}  // namespace scansurf
