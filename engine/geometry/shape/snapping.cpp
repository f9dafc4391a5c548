// Snapping crowded vertices onto their lattice point (Raman & Wenger, "Quality isosurface mesh
// generation using an extended marching cubes lookup table", EuroVis 2008; the multi-material
// counterpart is the snap step of Bronson, Levine & Whitaker's lattice cleaving).
//
// Where a separating surface passes within a few hundredths of a voxel of a voxel centre p, the
// vertices on p's lattice edges crowd around p and the triangles between them and the vertices
// further out are slivers. Raman and Wenger give p the isovalue instead: the surface passes
// through p, every vertex on p's edges becomes p, the triangles with two such vertices vanish.
//
// Why the surfaces still never cross (the argument of smoothing.cpp, extended). Every vertex maps
// to itself or, once a corner of its lattice edge has snapped, to that corner (the first one to
// snap keeps it); a triangle with two vertices on one point vanishes. A triangle of tetrahedron T
// keeps its vertices in T (edge points or T's corners), so it stays in T. Its orientation stays:
// each vertex slides along its own edge towards a corner, and a triangle through points of three
// edges of T can only flatten if two of its points meet, which makes it vanish instead. On a
// face F of T its curve is the image of the curve it had there, the same from both sides: a
// vertex off F that lands on F's corner c shares its triangle with a vertex on an edge of F at c
// (the only edges of F it can meet), which lands on c too, so that triangle vanishes; no kept
// triangle lies in F unless all three of its corners snapped, which is refused. Topology: the
// triangles of the vertices that merge (as the snaps before left them) must form a disk whose
// rim is one cycle holding every other vertex of them, so that the disk shrinks to a fan around
// p with the same rim (no handle, component or pinch lost). Points of one parity class are
// never neighbours, so their stars are apart and they snap at once.
#include "geometry/shape/snapping.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <utility>

#include "core/parallel.h"
#include "geometry/smoothing/carrier_projection.h"
#include "geometry/smoothing/edge_corners.h"

namespace scansurf {
namespace {

using Key = std::uint64_t;

// A lattice point that a vertex crowds, and how closely (fraction of the edge).
struct Candidate {
  Key point;
  double along;
  bool operator<(const Candidate& o) const { return point != o.point ? point < o.point : along < o.along; }
};

// The lattice points the vertices crowd (edgeCornersOf's corners), sorted by point, then by
// how closely.
std::vector<Candidate> findCandidates(const MultiLabelMesh& mesh, const Grid& grid, double fraction,
                                      const std::vector<EdgeCorners>& corners, int threads) {
  const std::size_t count = mesh.vertexCount();
  std::vector<std::vector<Candidate>> perChunk(static_cast<std::size_t>(chunkCount(count, threads)));
  parallelChunks(count, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      if (corners[v].b == 0) continue;
      const Vec3 a = cornerPosition(grid, cornerOf(corners[v].a).data()), b = cornerPosition(grid, cornerOf(corners[v].b).data());
      const Vec3 x{mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
      const double t = glm::dot(x - a, b - a) / glm::dot(b - a, b - a);
      if (t <= fraction) perChunk[static_cast<std::size_t>(chunk)].push_back({corners[v].a, t});
      if (1 - t <= fraction) perChunk[static_cast<std::size_t>(chunk)].push_back({corners[v].b, 1 - t});
    }
  });
  std::vector<Candidate> out;
  for (const auto& c : perChunk) out.insert(out.end(), c.begin(), c.end());
  std::sort(out.begin(), out.end());
  return out;
}

// One bit per voxel centre of the grid: is it a candidate?
class LatticeBits {
 public:
  explicit LatticeBits(const Grid& grid)
      : nx_(static_cast<std::uint64_t>(grid.nx)),
        ny_(static_cast<std::uint64_t>(grid.ny)),
        words_((nx_ * ny_ * static_cast<std::uint64_t>(grid.nz) + 63) / 64, 0) {}
  bool inside(Key p) const {
    const auto c = cornerOf(p);
    return static_cast<std::uint64_t>(c[0]) < nx_ && static_cast<std::uint64_t>(c[1]) < ny_ && indexOf(p) / 64 < words_.size();
  }
  bool test(Key p) const { return inside(p) && (words_[indexOf(p) / 64] >> (indexOf(p) % 64) & 1); }
  void set(Key p) { words_[indexOf(p) / 64] |= std::uint64_t{1} << (indexOf(p) % 64); }

 private:
  std::uint64_t indexOf(Key p) const {
    const auto c = cornerOf(p);
    return static_cast<std::uint64_t>(c[0]) + nx_ * (static_cast<std::uint64_t>(c[1]) + ny_ * static_cast<std::uint64_t>(c[2]));
  }
  std::uint64_t nx_, ny_;
  std::vector<std::uint64_t> words_;
};

// Items filed under buckets: per bucket, its items ascending.
struct Filing {
  std::vector<std::size_t> start;    // size buckets + 1
  std::vector<std::uint32_t> items;  // per bucket, ascending
  std::span<const std::uint32_t> of(std::size_t b) const { return {items.data() + start[b], start[b + 1] - start[b]}; }
};

// Files items 0..count-1 under the buckets that bucketsOf(item, out) appends (each at most once
// per item), in parallel and in item order: each chunk counts its items per bucket, then writes
// them after those of the buckets before and of the chunks before (a counting sort).
template <typename BucketsOf>
Filing file(std::size_t count, std::size_t buckets, int threads, const BucketsOf& bucketsOf) {
  const auto chunks = static_cast<std::size_t>(chunkCount(count, threads));
  std::vector<std::vector<std::size_t>> at(chunks, std::vector<std::size_t>(buckets, 0));
  parallelChunks(count, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> under;
    for (std::size_t i = begin; i < end; ++i) {
      under.clear();
      bucketsOf(i, under);
      for (std::uint32_t b : under) ++at[static_cast<std::size_t>(chunk)][b];
    }
  });
  Filing out;
  out.start.assign(buckets + 1, 0);
  std::size_t total = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    out.start[b] = total;
    for (std::size_t c = 0; c < chunks; ++c) total += std::exchange(at[c][b], total);
  }
  out.start[buckets] = total;
  out.items.resize(total);
  parallelChunks(count, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> under;
    for (std::size_t i = begin; i < end; ++i) {
      under.clear();
      bucketsOf(i, under);
      for (std::uint32_t b : under) out.items[at[static_cast<std::size_t>(chunk)][b]++] = static_cast<std::uint32_t>(i);
    }
  });
  return out;
}

// Per candidate point (ascending): its closest vertex's fraction, the vertices on its lattice
// edges (they merge into it) and the triangles that hold any of them (its star).
struct Stars {
  std::vector<Key> points;
  std::vector<double> along;
  Filing vertices, triangles;
};

Stars starsOf(const MultiLabelMesh& mesh, const std::vector<Candidate>& candidates, const std::vector<EdgeCorners>& corners,
              const LatticeBits& bits, int threads) {
  Stars out;
  for (const Candidate& c : candidates)  // sorted: the first of each point is its closest
    if (out.points.empty() || out.points.back() != c.point) out.points.push_back(c.point), out.along.push_back(c.along);
  constexpr std::uint32_t kNone = ~0u;
  std::vector<std::array<std::uint32_t, 2>> pointOf(corners.size(), {kNone, kNone});  // per vertex, per corner
  parallelChunks(corners.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
      for (int k = 0; k < 2; ++k)
        if (const Key p = k ? corners[v].b : corners[v].a; corners[v].b != 0 && bits.test(p))
          pointOf[v][static_cast<std::size_t>(k)] =
              static_cast<std::uint32_t>(std::lower_bound(out.points.begin(), out.points.end(), p) - out.points.begin());
  });
  out.vertices = file(corners.size(), out.points.size(), threads, [&](std::size_t v, std::vector<std::uint32_t>& under) {
    for (std::uint32_t p : pointOf[v])
      if (p != kNone) under.push_back(p);
  });
  out.triangles = file(mesh.triangleCount(), out.points.size(), threads, [&](std::size_t t, std::vector<std::uint32_t>& under) {
    for (int c = 0; c < 3; ++c)
      for (std::uint32_t p : pointOf[mesh.triangles[3 * t + static_cast<std::size_t>(c)]])
        if (p != kNone && std::find(under.begin(), under.end(), p) == under.end()) under.push_back(p);
  });
  return out;
}

// What the snaps so far made of the mesh: per vertex, the snapped point it merged into (an index
// into the points chosen) or kKept; per triangle, whether it collapsed.
struct SnapState {
  static constexpr std::uint32_t kKept = ~0u;
  std::vector<std::uint32_t> pointOf;
  std::vector<char> collapsed;
  std::vector<Key> points;  // in the order chosen
  // A vertex's image: itself, or its point (numbered after the vertices).
  std::uint32_t image(std::uint32_t v) const {
    return pointOf[v] == kKept ? v : static_cast<std::uint32_t>(pointOf.size()) + pointOf[v];
  }
};

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

// Point i's star as the snaps so far left it: the vertices still on its edges (they merge) and
// the live triangles that hold one of them.
void currentStar(const MultiLabelMesh& mesh, const Stars& stars, std::size_t i, const SnapState& state, StarScratch& s) {
  s.merging.clear(), s.triangles.clear();
  for (std::uint32_t v : stars.vertices.of(i))
    if (state.pointOf[v] == SnapState::kKept) s.merging.push_back(v);
  for (std::uint32_t t : stars.triangles.of(i)) {
    if (state.collapsed[t]) continue;
    for (int c = 0; c < 3; ++c)
      if (std::binary_search(s.merging.begin(), s.merging.end(),
                             mesh.triangles[3 * std::size_t{t} + static_cast<std::size_t>(c)])) {
        s.triangles.push_back(t);
        break;
      }
  }
}

// The merged vertices' triangles, as the snaps so far left them: one label pair, on lattice
// edges, a disk (Euler characteristic 1) whose rim is one cycle, and no kept triangle whose
// other corners are both snapped points (it would lie in a lattice face, as its neighbour's may).
bool starIsDisk(const MultiLabelMesh& mesh, const std::vector<EdgeCorners>& corners, const SnapState& state, StarScratch& s) {
  s.vertices.clear(), s.rim.clear(), s.edges.clear();
  if (s.triangles.empty()) return false;
  const std::size_t first = s.triangles.front();
  const auto points = static_cast<std::uint32_t>(state.pointOf.size());
  for (std::uint32_t t : s.triangles) {
    if (mesh.labels[2 * t] != mesh.labels[2 * first] || mesh.labels[2 * t + 1] != mesh.labels[2 * first + 1]) return false;
    const std::uint32_t* tri = &mesh.triangles[3 * std::size_t{t}];
    std::uint32_t image[3];
    int merged = 0, at = 0;
    for (int c = 0; c < 3; ++c) {
      if (corners[tri[c]].b == 0) return false;
      if (std::binary_search(s.merging.begin(), s.merging.end(), tri[c])) ++merged, at = c;
      image[c] = state.image(tri[c]);
    }
    for (int c = 0; c < 3; ++c) s.vertices.push_back(image[c]), s.edges.push_back(std::minmax(image[c], image[(c + 1) % 3]));
    if (merged != 1) continue;
    const std::uint32_t u = image[(at + 1) % 3], w = image[(at + 2) % 3];
    if (u >= points && w >= points) return false;
    s.rim.emplace_back(u, w);
  }
  std::sort(s.vertices.begin(), s.vertices.end());
  std::sort(s.edges.begin(), s.edges.end());
  const auto vertices = std::unique(s.vertices.begin(), s.vertices.end()) - s.vertices.begin();
  const auto edges = std::unique(s.edges.begin(), s.edges.end()) - s.edges.begin();
  // Every vertex that does not merge lies on the rim, or its whole fan would collapse.
  const auto inside = static_cast<std::ptrdiff_t>(s.merging.size());
  return vertices - edges + static_cast<std::ptrdiff_t>(s.triangles.size()) == 1 &&
         vertices - inside == static_cast<std::ptrdiff_t>(s.rim.size()) && rimIsOneCycle(s.rim);
}

// Merges the star's vertices into point `index` and marks the triangles that collapse.
void snapPoint(const MultiLabelMesh& mesh, std::uint32_t index, const StarScratch& s, SnapState& state) {
  for (std::uint32_t v : s.merging) state.pointOf[v] = index;
  for (std::uint32_t t : s.triangles) {
    int merged = 0;
    for (int c = 0; c < 3; ++c)
      merged += state.pointOf[mesh.triangles[3 * std::size_t{t} + static_cast<std::size_t>(c)]] == index;
    if (merged > 1) state.collapsed[t] = 1;
  }
}

// A lattice point's parity class (x, y and z index each odd or even): a lattice edge steps by 0
// or 1 along each axis, so two points of one class are never neighbours, and their stars share
// no vertex and no triangle.
int parityOf(Key p) {
  const auto c = cornerOf(p);
  return (c[0] & 1) | (c[1] & 1) << 1 | (c[2] & 1) << 2;
}

// Snaps the candidates of one parity class whose stars, as the snaps before left them, are disks:
// all at once, since their stars are apart. Indices in the order of `members`.
void snapClass(const MultiLabelMesh& mesh, const Stars& stars, const std::vector<EdgeCorners>& corners,
               const std::vector<std::size_t>& members, SnapState& state, int threads) {
  std::vector<std::uint32_t> index(members.size(), SnapState::kKept);
  parallelChunks(members.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    StarScratch s;
    for (std::size_t k = begin; k < end; ++k) {
      currentStar(mesh, stars, members[k], state, s);
      index[k] = starIsDisk(mesh, corners, state, s) ? 0 : SnapState::kKept;
    }
  });
  for (std::size_t k = 0; k < members.size(); ++k)
    if (index[k] != SnapState::kKept) {
      index[k] = static_cast<std::uint32_t>(state.points.size());
      state.points.push_back(stars.points[members[k]]);
    }
  parallelChunks(members.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    StarScratch s;
    for (std::size_t k = begin; k < end; ++k)
      if (index[k] != SnapState::kKept) {
        currentStar(mesh, stars, members[k], state, s);
        snapPoint(mesh, index[k], s, state);
      }
  });
}

// Snaps every candidate whose star, as the snaps before it left it, is a disk, so that
// neighbours can both snap: the most crowded first (four bands of the fraction, halving), each
// band one parity class after another. The result does not depend on the thread count.
SnapState choosePoints(const MultiLabelMesh& mesh, const Stars& stars, const std::vector<EdgeCorners>& corners, double fraction,
                       TriangleShapeReport& report, int threads) {
  SnapState state;
  state.pointOf.assign(mesh.vertexCount(), SnapState::kKept);
  state.collapsed.assign(mesh.triangleCount(), 0);
  double below = -1;  // the first band takes every fraction up to its bound
  for (const double band : {fraction / 8, fraction / 4, fraction / 2, fraction}) {
    std::vector<std::size_t> classes[8];
    for (std::size_t i = 0; i < stars.points.size(); ++i)
      if (stars.along[i] > below && stars.along[i] <= band) classes[parityOf(stars.points[i])].push_back(i);
    for (const std::vector<std::size_t>& members : classes) snapClass(mesh, stars, corners, members, state, threads);
    below = band;
  }
  report.candidates = stars.points.size();
  return state;
}

// The triangles with each vertex renumbered (merged ones to their point's vertex), those that
// collapsed dropped, in order; in parallel chunks, each writing after the ones before it.
void remapTriangles(const MultiLabelMesh& mesh, const std::vector<std::uint32_t>& pointOf,
                    const std::vector<std::uint32_t>& newIndex, const std::vector<std::uint32_t>& newPoint, MultiLabelMesh& out,
                    TriangleShapeReport& report, int threads) {
  const std::size_t count = mesh.triangleCount();
  const auto mapped = [&](std::size_t t, int c) {
    const std::uint32_t v = mesh.triangles[3 * t + c];
    return pointOf[v] == SnapState::kKept ? newIndex[v] : newPoint[pointOf[v]];
  };
  const auto collapsed = [&](std::size_t t) {
    const std::uint32_t a = mapped(t, 0), b = mapped(t, 1), c = mapped(t, 2);
    return a == b || b == c || c == a;
  };
  const int chunks = chunkCount(count, threads);
  std::vector<std::size_t> kept(static_cast<std::size_t>(chunks) + 1, 0);
  parallelChunks(count, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) kept[static_cast<std::size_t>(chunk) + 1] += !collapsed(t);
  });
  for (std::size_t c = 1; c < kept.size(); ++c) kept[c] += kept[c - 1];
  out.triangles.resize(3 * kept.back());
  out.labels.resize(2 * kept.back());
  parallelChunks(count, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    std::size_t at = kept[static_cast<std::size_t>(chunk)];
    for (std::size_t t = begin; t < end; ++t) {
      if (collapsed(t)) continue;
      for (int c = 0; c < 3; ++c) out.triangles[3 * at + static_cast<std::size_t>(c)] = mapped(t, c);
      out.labels[2 * at] = mesh.labels[2 * t], out.labels[2 * at + 1] = mesh.labels[2 * t + 1];
      ++at;
    }
  });
  report.removedTriangles = count - kept.back();
}

// Rebuilds the mesh with each snapped point's merged vertices replaced by one vertex at it,
// vertices in key order, the triangles that collapsed dropped.
void mergeIntoPoints(MultiLabelMesh& mesh, const Grid& grid, const SnapState& state, std::vector<bool>& onSheet,
                     TriangleShapeReport& report, int threads) {
  const std::size_t count = mesh.vertexCount();
  std::vector<std::uint32_t> byKey(state.points.size());  // the points in key order
  for (std::uint32_t i = 0; i < byKey.size(); ++i) byKey[i] = i;
  std::sort(byKey.begin(), byKey.end(), [&](std::uint32_t a, std::uint32_t b) { return state.points[a] < state.points[b]; });
  MultiLabelMesh out;
  std::vector<bool> sheet;
  std::vector<std::uint32_t> newIndex(count), newPoint(state.points.size());
  std::size_t p = 0;
  const auto emitPoint = [&] {
    const Key key = state.points[byKey[p]];
    const Vec3 x = cornerPosition(grid, cornerOf(key).data());
    newPoint[byKey[p++]] = static_cast<std::uint32_t>(out.keys.size());
    out.keys.push_back(key), sheet.push_back(false);
    for (int a = 0; a < 3; ++a) out.positions.push_back(static_cast<float>(x[a]));
  };
  for (std::size_t v = 0; v < count; ++v) {
    if (state.pointOf[v] != SnapState::kKept) {
      ++report.mergedVertices;
      continue;
    }
    while (p < byKey.size() && state.points[byKey[p]] < mesh.keys[v]) emitPoint();
    newIndex[v] = static_cast<std::uint32_t>(out.keys.size());
    out.keys.push_back(mesh.keys[v]), sheet.push_back(v < onSheet.size() && onSheet[v]);
    out.positions.insert(out.positions.end(), &mesh.positions[3 * v], &mesh.positions[3 * v] + 3);
  }
  while (p < byKey.size()) emitPoint();
  remapTriangles(mesh, state.pointOf, newIndex, newPoint, out, report, threads);
  mesh = std::move(out);
  onSheet = std::move(sheet);
}

}  // namespace

TriangleShapeReport snapToLattice(MultiLabelMesh& mesh, const Grid& grid, double fraction, std::vector<bool>& onSheet,
                                  int threads) {
  TriangleShapeReport report;
  report.ran = true;
  report.fraction = fraction;
  if (!(fraction > 0) || mesh.keys.size() != mesh.vertexCount() || mesh.triangleCount() == 0) return report;
  const std::vector<EdgeCorners> corners = edgeCornersOf(mesh, threads);
  const std::vector<Candidate> candidates = findCandidates(mesh, grid, fraction, corners, threads);
  LatticeBits bits(grid);
  for (const Candidate& c : candidates) bits.set(c.point);
  const Stars stars = starsOf(mesh, candidates, corners, bits, threads);
  const SnapState state = choosePoints(mesh, stars, corners, fraction, report, threads);
  report.points = state.points.size();
  if (!state.points.empty()) mergeIntoPoints(mesh, grid, state, onSheet, report, threads);
  return report;
}

double snapFractionFor(const Grid& grid, const std::vector<bool>& contourLayers, double fraction) {
  std::vector<double> planes;
  for (std::size_t k = 0; k < contourLayers.size() && k < grid.layerZ.size(); ++k)
    if (contourLayers[k]) planes.push_back(grid.layerZ[k]);
  if (planes.size() < 2) planes = grid.layerZ;
  if (planes.size() < 2) return fraction;
  std::vector<double> gaps(planes.size() - 1);
  for (std::size_t i = 0; i + 1 < planes.size(); ++i) gaps[i] = planes[i + 1] - planes[i];
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  const double pixel = std::min(grid.spacingX, grid.spacingY);
  return fraction * std::min(1.0, gaps[gaps.size() / 2] / (2 * pixel));
}

void accumulate(TriangleShapeReport& into, const TriangleShapeReport& layer) {
  into.ran = into.ran || layer.ran;
  into.fraction = std::max(into.fraction, layer.fraction);
  into.candidates += layer.candidates, into.points += layer.points, into.mergedVertices += layer.mergedVertices;
  into.removedTriangles += layer.removedTriangles, into.quadsFlipped += layer.quadsFlipped, into.cubeFans += layer.cubeFans;
  into.fanVerticesRemoved += layer.fanVerticesRemoved;
  into.seconds += layer.seconds;
}

}  // namespace scansurf
