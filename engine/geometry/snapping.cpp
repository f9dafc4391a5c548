// Snapping crowded vertices onto their lattice point (Raman & Wenger, "Quality isosurface mesh
// generation using an extended marching cubes lookup table", EuroVis 2008; the multi-material
// counterpart is the snap step of Bronson, Levine & Whitaker's lattice cleaving).
//
// Where a separating surface passes within a few hundredths of a voxel of a voxel centre p, the
// vertices on p's lattice edges crowd around p and the triangles between them and the vertices
// further out are slivers. Raman and Wenger give p the isovalue instead: the surface passes
// through p, every vertex on p's edges becomes p, the triangles with two such vertices vanish.
//
// Why the surfaces still never cross (the argument of smoothing.cpp, extended): p's star has two
// labels, so every tetrahedron T around p holds at most one triangle once snapped: (3+1) with p
// alone on its side vanishes; (3+1) with p among three becomes (p, x, y), x and y on T's edges
// opposite p; (2+2) loses the triangle with both of p's vertices and keeps (p, x, y). Each kept
// triangle lies in T, and moving its vertex from its edge point to p never passes through the
// plane of x, y and T's corner of the other label, so it keeps its orientation. On a face of T
// at p, the surface's curve is the segment from p to the vertex on the opposite edge, or p alone,
// the same from both sides. Two snapped points are never neighbours, so no tetrahedron has two.
// Topology: the merged vertices' triangles must form a disk whose rim is one cycle, so that the
// disk shrinks to a fan around p with the same rim (no handle, no component, no pinch lost).
#include "geometry/snapping.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <unordered_set>

#include "core/parallel.h"
#include "geometry/assembly.h"
#include "geometry/carrier_projection.h"
#include "geometry/incident_triangles.h"

namespace scansurf {
namespace {

using Key = std::uint64_t;
using Coords = std::array<std::int64_t, 3>;  // in twelfths of a voxel

Coords unpack(Key key) {
  return {static_cast<std::int64_t>(key & kKeyMask), static_cast<std::int64_t>((key >> kKeyBits) & kKeyMask),
          static_cast<std::int64_t>(key >> (2 * kKeyBits))};
}

// The key at c + sign * step * e, for direction e in 1..7 (bit a: a step along axis a); false
// when it leaves the key range.
bool shifted(Key key, int e, int sign, std::int64_t step, Key& out) {
  const Coords c = unpack(key);
  out = 0;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t k = c[a] + sign * step * ((e >> a) & 1);
    if (k < 0 || k > static_cast<std::int64_t>(kKeyMask)) return false;
    out |= static_cast<Key>(k) << (a * kKeyBits);
  }
  return true;
}

Key pointKey(const int corner[3]) {
  Key out = 0;
  for (int a = 0; a < 3; ++a) out |= static_cast<Key>(12 * corner[a]) << (a * kKeyBits);
  return out;
}

// A lattice point that a vertex crowds, and how closely (fraction of the edge).
struct Candidate {
  Key point;
  double along;
  bool operator<(const Candidate& o) const { return point != o.point ? point < o.point : along < o.along; }
};

// Per vertex: on a lattice edge? And the candidates its position makes.
std::vector<Candidate> findCandidates(const MultiLabelMesh& mesh, const Grid& grid, double fraction, std::vector<char>& onEdge,
                                      int threads) {
  const std::size_t count = mesh.vertexCount();
  onEdge.assign(count, 0);
  std::vector<std::vector<Candidate>> perChunk(static_cast<std::size_t>(chunkCount(count, threads)));
  parallelChunks(count, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const Carrier carrier = carrierOfKey(mesh.keys[v]);
      if (carrier.count != 2) continue;
      onEdge[v] = 1;
      const Vec3 a = cornerPosition(grid, carrier.corners[0]), b = cornerPosition(grid, carrier.corners[1]);
      const Vec3 x{mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
      const double t = glm::dot(x - a, b - a) / glm::dot(b - a, b - a);
      if (t <= fraction) perChunk[static_cast<std::size_t>(chunk)].push_back({pointKey(carrier.corners[0]), t});
      if (1 - t <= fraction) perChunk[static_cast<std::size_t>(chunk)].push_back({pointKey(carrier.corners[1]), 1 - t});
    }
  });
  std::vector<Candidate> out;
  for (const auto& c : perChunk) out.insert(out.end(), c.begin(), c.end());
  std::sort(out.begin(), out.end());
  return out;
}

// The vertices on p's 14 lattice edges (keys 12 p +- 6 e), ascending.
void mergingVertices(std::span<const Key> keys, Key p, std::vector<std::uint32_t>& out) {
  out.clear();
  for (int e = 1; e < 8; ++e)
    for (int sign : {-1, 1}) {
      Key key;
      if (!shifted(p, e, sign, 6, key)) continue;
      const auto it = std::lower_bound(keys.begin(), keys.end(), key);
      if (it != keys.end() && *it == key) out.push_back(static_cast<std::uint32_t>(it - keys.begin()));
    }
  std::sort(out.begin(), out.end());
}

struct StarScratch {
  std::vector<std::uint32_t> merging, triangles, vertices;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> rim, edges;
};

// The rim (each kept triangle's edge opposite its merged vertex, directed) is one cycle.
bool rimIsOneCycle(std::vector<std::pair<std::uint32_t, std::uint32_t>>& rim) {
  if (rim.size() < 3) return false;
  std::sort(rim.begin(), rim.end());
  for (std::size_t i = 1; i < rim.size(); ++i)
    if (rim[i].first == rim[i - 1].first) return false;
  std::uint32_t at = rim.front().first;
  for (std::size_t step = 0; step < rim.size(); ++step) {
    const auto it = std::lower_bound(rim.begin(), rim.end(), std::make_pair(at, std::uint32_t{0}));
    if (it == rim.end() || it->first != at) return false;
    at = it->second;
    if (at == rim.front().first) return step + 1 == rim.size();
  }
  return false;
}

// The merged vertices' triangles: one label pair, lattice-edge vertices only, a disk (Euler
// characteristic 1) whose rim is one cycle.
bool starIsDisk(const MultiLabelMesh& mesh, const IncidentTriangles& incident, const std::vector<char>& onEdge, StarScratch& s) {
  s.triangles.clear(), s.vertices.clear(), s.rim.clear(), s.edges.clear();
  for (std::uint32_t m : s.merging)
    s.triangles.insert(s.triangles.end(), &incident.list[incident.start[m]], &incident.list[incident.start[m + 1]]);
  std::sort(s.triangles.begin(), s.triangles.end());
  s.triangles.erase(std::unique(s.triangles.begin(), s.triangles.end()), s.triangles.end());
  if (s.triangles.empty()) return false;
  const std::size_t first = s.triangles.front();
  for (std::uint32_t t : s.triangles) {
    if (mesh.labels[2 * t] != mesh.labels[2 * first] || mesh.labels[2 * t + 1] != mesh.labels[2 * first + 1]) return false;
    const std::uint32_t* tri = &mesh.triangles[3 * std::size_t{t}];
    int merged = 0, at = 0;
    for (int c = 0; c < 3; ++c) {
      if (!onEdge[tri[c]]) return false;
      if (std::binary_search(s.merging.begin(), s.merging.end(), tri[c])) ++merged, at = c;
      s.vertices.push_back(tri[c]);
      s.edges.push_back(std::minmax(tri[c], tri[(c + 1) % 3]));
    }
    if (merged == 1) s.rim.emplace_back(tri[(at + 1) % 3], tri[(at + 2) % 3]);
  }
  std::sort(s.vertices.begin(), s.vertices.end());
  std::sort(s.edges.begin(), s.edges.end());
  const auto vertices = std::unique(s.vertices.begin(), s.vertices.end()) - s.vertices.begin();
  const auto edges = std::unique(s.edges.begin(), s.edges.end()) - s.edges.begin();
  return vertices - edges + static_cast<std::ptrdiff_t>(s.triangles.size()) == 1 && rimIsOneCycle(s.rim);
}

// The points to snap: the closest-crowded first, each unless a neighbour was taken.
std::vector<Key> choosePoints(const MultiLabelMesh& mesh, const std::vector<Candidate>& candidates,
                              const std::vector<char>& onEdge, int threads) {
  std::vector<Candidate> best;  // per point its closest vertex (candidates are sorted)
  for (const Candidate& c : candidates)
    if (best.empty() || best.back().point != c.point) best.push_back(c);
  const IncidentTriangles incident = incidentTriangles(mesh);
  std::vector<char> disk(best.size(), 0);
  parallelChunks(best.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    StarScratch s;
    for (std::size_t i = begin; i < end; ++i) {
      mergingVertices(mesh.keys, best[i].point, s.merging);
      disk[i] = starIsDisk(mesh, incident, onEdge, s);
    }
  });
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < best.size(); ++i)
    if (disk[i]) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return best[a].along != best[b].along ? best[a].along < best[b].along : best[a].point < best[b].point;
  });
  std::unordered_set<Key> taken;
  std::vector<Key> out;
  for (std::size_t i : order) {
    bool free = true;
    for (int e = 1; e < 8 && free; ++e)
      for (int sign : {-1, 1}) {
        Key n;
        if (shifted(best[i].point, e, sign, 12, n) && taken.count(n)) free = false;
      }
    if (free) taken.insert(best[i].point), out.push_back(best[i].point);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Rebuilds the mesh with each chosen point's merged vertices replaced by one vertex at it,
// vertices in key order, the triangles that collapsed dropped.
void mergeIntoPoints(MultiLabelMesh& mesh, const Grid& grid, const std::vector<Key>& points, std::vector<bool>& onSheet,
                     SnapReport& report) {
  constexpr std::uint32_t kKept = ~0u;
  const std::size_t count = mesh.vertexCount();
  std::vector<std::uint32_t> pointOf(count, kKept);
  std::vector<std::uint32_t> merging;
  for (std::size_t i = 0; i < points.size(); ++i) {
    mergingVertices(mesh.keys, points[i], merging);
    for (std::uint32_t m : merging) pointOf[m] = static_cast<std::uint32_t>(i);
    report.mergedVertices += merging.size();
  }
  MultiLabelMesh out;
  std::vector<bool> sheet;
  std::vector<std::uint32_t> newIndex(count), newPoint(points.size());
  std::size_t p = 0;
  const auto emitPoint = [&] {
    const Coords c = unpack(points[p]);
    const int corner[3] = {static_cast<int>(c[0] / 12), static_cast<int>(c[1] / 12), static_cast<int>(c[2] / 12)};
    const Vec3 x = cornerPosition(grid, corner);
    newPoint[p++] = static_cast<std::uint32_t>(out.keys.size());
    out.keys.push_back(pointKey(corner)), sheet.push_back(false);
    for (int a = 0; a < 3; ++a) out.positions.push_back(static_cast<float>(x[a]));
  };
  for (std::size_t v = 0; v < count; ++v) {
    if (pointOf[v] != kKept) continue;
    while (p < points.size() && points[p] < mesh.keys[v]) emitPoint();
    newIndex[v] = static_cast<std::uint32_t>(out.keys.size());
    out.keys.push_back(mesh.keys[v]), sheet.push_back(v < onSheet.size() && onSheet[v]);
    out.positions.insert(out.positions.end(), &mesh.positions[3 * v], &mesh.positions[3 * v] + 3);
  }
  while (p < points.size()) emitPoint();
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    std::uint32_t tri[3];
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = mesh.triangles[3 * t + c];
      tri[c] = pointOf[v] == kKept ? newIndex[v] : newPoint[pointOf[v]];
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      ++report.removedTriangles;
      continue;
    }
    out.triangles.insert(out.triangles.end(), tri, tri + 3);
    out.labels.insert(out.labels.end(), &mesh.labels[2 * t], &mesh.labels[2 * t] + 2);
  }
  mesh = std::move(out);
  onSheet = std::move(sheet);
}

}  // namespace

SnapReport snapToLattice(MultiLabelMesh& mesh, const Grid& grid, double fraction, std::vector<bool>& onSheet, int threads) {
  SnapReport report;
  if (!(fraction > 0) || mesh.keys.size() != mesh.vertexCount() || mesh.triangleCount() == 0) return report;
  std::vector<char> onEdge;
  const std::vector<Candidate> candidates = findCandidates(mesh, grid, fraction, onEdge, threads);
  const std::vector<Key> points = choosePoints(mesh, candidates, onEdge, threads);
  report.points = points.size();
  if (!points.empty()) mergeIntoPoints(mesh, grid, points, onSheet, report);
  return report;
}

}  // namespace scansurf
