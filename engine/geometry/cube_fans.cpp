// Re-triangulating the cubes' fans (issue 28). In a cube whose separating surface carries two
// labels, the Freudenthal cut puts a vertex on each cut cube edge and face diagonal and one on
// the body diagonal, and fans the surface around that last one; marching cubes (Lorensen &
// Cline 1987) triangulates the same rim with no inner vertex.
//
// Why the surfaces still never cross. The rim's vertices lie on the cube's faces (on cube edges,
// face diagonals or corners) and no new edge joins two vertices of one face, so every new
// triangle but its rim edges lies in the open cube, where no other cube's triangle is (each lies
// in its own closed tetrahedron); the rim edges are the ones the fan had, shared with the
// neighbouring cubes. Inside the cube the new triangles are the only ones (the cube carried one
// disk), and they cannot meet each other: each projects along the disk's axis with the same
// orientation (exact), and so does the rim, one-to-one, so the projection maps the disk onto the
// rim's inside one-to-one (a locally one-to-one map of a disk with a simple boundary curve is).
// The disk has the fan's rim, so it splits the cube's corners as the fan did: the labels on
// either side stay; the vertex removed was inside the cube, on no other cube's triangle.
#include "geometry/cube_fans.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/parallel.h"
#include "geometry/assembly.h"
#include "geometry/triangle_intersection.h"
#include "geometry/vec3.h"

namespace scansurf {
namespace {

constexpr double kTolerance = 0.05;      // in-plane voxels: how far the removed vertex may lie from the disk
constexpr std::size_t kLongestRim = 16;  // longer rims (rare) keep their fan

using Key = std::uint64_t;

std::array<std::uint64_t, 3> unpack(Key k) { return {k & kKeyMask, (k >> kKeyBits) & kKeyMask, k >> (2 * kKeyBits)}; }

Vec3 at(const float* positions, std::uint32_t v) { return {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]}; }

// The cube of triangle t, in voxel indices packed like a key: the centroid of its vertices' keys
// (their carriers' centroids) lies strictly inside its tetrahedron's cube, since no triangle lies
// in a lattice face (smoothing.cpp, snapping.cpp).
Key cubeOf(const MultiLabelMesh& mesh, std::size_t t) {
  std::uint64_t sum[3] = {0, 0, 0};
  for (int c = 0; c < 3; ++c) {
    const auto k = unpack(mesh.keys[mesh.triangles[3 * t + static_cast<std::size_t>(c)]]);
    for (int a = 0; a < 3; ++a) sum[a] += k[a];
  }
  return packVertexKey(sum[0] / 36, sum[1] / 36, sum[2] / 36);
}

// Bit 2a (2a + 1): the key lies on the cube's low (high) face across axis a; 0: inside.
int facesOf(Key key, Key cube) {
  const auto k = unpack(key), c = unpack(cube);
  int mask = 0;
  for (int a = 0; a < 3; ++a) mask |= (k[a] == 12 * c[a] ? 1 : 0) << (2 * a) | (k[a] == 12 * c[a] + 12 ? 2 : 0) << (2 * a);
  return mask;
}

// The cosine of a triangle's smallest angle (opposite its shortest side) from its sides'
// squares: the smaller, the better shaped.
double sharpness(double ab, double bc, double ca) {
  const double shortest = std::min({ab, bc, ca});
  if (!(shortest > 0)) return 1;
  return (ab + bc + ca - 2 * shortest) / (2 * std::sqrt(ab * bc * ca / shortest));
}

double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = glm::cross(b - a, c - a);
  const double twiceArea = glm::length(n);
  if (twiceArea > 0) {  // over the triangle: the distance to its plane
    const Vec3 unit = n / twiceArea;
    const Vec3 q = p - unit * glm::dot(p - a, unit);
    if (glm::dot(glm::cross(b - a, q - a), n) >= 0 && glm::dot(glm::cross(c - b, q - b), n) >= 0 &&
        glm::dot(glm::cross(a - c, q - c), n) >= 0)
      return std::abs(glm::dot(p - a, unit));
  }
  const auto segment = [&](const Vec3& s, const Vec3& e) {
    const Vec3 d = e - s;
    const double t = std::clamp(glm::dot(p - s, d) / std::max(glm::dot(d, d), 1e-300), 0.0, 1.0);
    return glm::length(p - (s + d * t));
  };
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

// Whether the disk (rim of n vertices, its n - 2 triangles) projects one-to-one along `view`'s
// axis: every triangle turns the view's way (exact), and no two rim edges meet but neighbours at
// their shared vertex (exact; collinear touches count as meeting).
bool projectsOneToOne(const float* positions, const std::uint32_t* rim, std::size_t n, const std::uint32_t* triangles, int view) {
  const int axis = view % 3, u = (axis + 1) % 3, v = (axis + 2) % 3, sign = view < 3 ? 1 : -1;
  for (std::size_t t = 0; t + 2 < n; ++t)
    if (orient2d(at(positions, triangles[3 * t]), at(positions, triangles[3 * t + 1]), at(positions, triangles[3 * t + 2]), u,
                 v) != sign)
      return false;
  const auto p = [&](std::size_t i) { return at(positions, rim[i % n]); };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = p(i), b = p(i + 1), c = p(i + 2);  // neighbours: no fold back along the shared vertex
    if (orient2d(a, b, c, u, v) == 0 && (a[u] - b[u]) * (c[u] - b[u]) + (a[v] - b[v]) * (c[v] - b[v]) > 0) return false;
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      const Vec3 q0 = p(j), q1 = p(j + 1);
      if (std::max(a[u], b[u]) < std::min(q0[u], q1[u]) || std::max(q0[u], q1[u]) < std::min(a[u], b[u]) ||
          std::max(a[v], b[v]) < std::min(q0[v], q1[v]) || std::max(q0[v], q1[v]) < std::min(a[v], b[v]))
        continue;  // apart
      if (orient2d(a, b, q0, u, v) * orient2d(a, b, q1, u, v) <= 0 && orient2d(q0, q1, a, u, v) * orient2d(q0, q1, b, u, v) <= 0)
        return false;
    }
  }
  return true;
}

// One cube's triangles [begin, end): its rim in their orientation and the vertex inside, if they
// carry one label pair and form a disk whose one inner vertex is the only vertex inside the cube.
struct Fan {
  std::vector<std::uint32_t> rim;
  std::uint32_t inner = 0;
};

bool fanOf(const MultiLabelMesh& mesh, std::size_t begin, std::size_t end, Key cube, Fan& fan) {
  const std::size_t count = end - begin;
  if (count < 3 || count > kLongestRim) return false;
  for (std::size_t t = begin + 1; t < end; ++t)
    if (mesh.labels[2 * t] != mesh.labels[2 * begin] || mesh.labels[2 * t + 1] != mesh.labels[2 * begin + 1]) return false;
  constexpr std::size_t kMost = kLongestRim + 1;              // a disk of F triangles around one vertex has F + 1
  std::array<std::uint32_t, kMost> ids;                       // the cube's vertices, local index -> mesh index
  std::array<std::array<std::uint8_t, kMost>, kMost> uses{};  // directed edge uses, local indices
  std::size_t distinct = 0;
  const auto local = [&](std::uint32_t v) -> std::size_t {
    for (std::size_t i = 0; i < distinct; ++i)
      if (ids[i] == v) return i;
    if (distinct == kMost) return kMost;
    ids[distinct] = v;
    return distinct++;
  };
  for (std::size_t t = begin; t < end; ++t) {
    std::size_t c[3];
    for (int k = 0; k < 3; ++k)
      if ((c[k] = local(mesh.triangles[3 * t + static_cast<std::size_t>(k)])) == kMost) return false;
    for (int k = 0; k < 3; ++k)
      if (++uses[c[k]][c[(k + 1) % 3]] > 1) return false;  // an edge used twice one way: no manifold
  }
  if (distinct != count + 1) return false;  // a disk around one inner vertex: F + 1 vertices, F rim edges
  std::array<std::uint8_t, kMost> next;
  next.fill(0xff);
  std::size_t rimEdges = 0;
  for (std::size_t a = 0; a < distinct; ++a)
    for (std::size_t b = 0; b < distinct; ++b)
      if (uses[a][b] && !uses[b][a]) {
        if (next[a] != 0xff) return false;  // a pinch
        next[a] = static_cast<std::uint8_t>(b), ++rimEdges;
      }
  if (rimEdges != count) return false;
  std::size_t inner = kMost;
  for (std::size_t a = 0; a < distinct; ++a)
    if (next[a] == 0xff) {
      if (inner != kMost) return false;
      inner = a;
    }
  if (inner == kMost) return false;
  // One cycle through every rim vertex: each once, back at the start after `count` steps.
  const std::size_t first = inner == 0 ? 1 : 0;
  std::array<bool, kMost> seen{};
  fan.rim.clear();
  for (std::size_t a = first, k = 0; k < count; ++k) {
    if (a == inner || seen[a]) return false;
    seen[a] = true;
    fan.rim.push_back(ids[a]);
    a = next[a];
    if (k + 1 == count && a != first) return false;
  }
  for (std::uint32_t v : fan.rim)
    if (facesOf(mesh.keys[v], cube) == 0) return false;
  fan.inner = ids[inner];
  return facesOf(mesh.keys[fan.inner], cube) == 0;
}

// The rim's triangulation with the largest smallest angle and no edge between two vertices on
// one cube face (dynamic programming over sub-polygons); false if there is none.
bool triangulateRim(const std::vector<Vec3>& p, const std::vector<int>& faces, const std::vector<std::uint32_t>& rim,
                    std::vector<std::uint32_t>& out) {
  const std::size_t n = p.size();
  std::array<double, kLongestRim * kLongestRim> square;  // squared distances between rim vertices
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) square[i * n + j] = glm::dot(p[j] - p[i], p[j] - p[i]);
  const auto allowed = [&](std::size_t i, std::size_t j) {
    return j - i == 1 || (i == 0 && j == n - 1) || !(faces[i] & faces[j]);
  };
  std::array<double, kLongestRim * kLongestRim> worst;  // of sub-polygon i..j: its sharpest triangle's sharpness
  std::array<std::uint8_t, kLongestRim * kLongestRim> split{};
  worst.fill(2);                                                      // 2: no triangulation
  for (std::size_t i = 0; i + 1 < n; ++i) worst[i * n + i + 1] = -1;  // an edge: no triangle yet
  for (std::size_t length = 2; length < n; ++length)
    for (std::size_t i = 0; i + length < n; ++i) {
      const std::size_t j = i + length;
      if (!allowed(i, j)) continue;
      for (std::size_t k = i + 1; k < j; ++k) {
        if (worst[i * n + k] > 1 || worst[k * n + j] > 1) continue;
        const double q =
            std::max({worst[i * n + k], worst[k * n + j], sharpness(square[i * n + k], square[k * n + j], square[i * n + j])});
        if (q < worst[i * n + j]) worst[i * n + j] = q, split[i * n + j] = static_cast<std::uint8_t>(k);
      }
    }
  if (worst[n - 1] > 1) return false;
  out.clear();
  std::array<std::pair<std::size_t, std::size_t>, kLongestRim> stack;
  std::size_t top = 0;
  stack[top++] = {0, n - 1};
  while (top > 0) {
    const auto [i, j] = stack[--top];
    if (j - i < 2) continue;
    const std::size_t k = split[i * n + j];
    out.insert(out.end(), {rim[i], rim[k], rim[j]});
    stack[top++] = {i, k}, stack[top++] = {k, j};
  }
  return true;
}

struct Scratch {
  Fan fan;
  std::vector<Vec3> points;
  std::vector<int> faces;
  std::vector<std::uint32_t> triangles;
};

// Plans cube [begin, end): on success its new triangles are in s.triangles and its view returned
// (else -1). Reads only the cube's triangles.
int planCube(const MultiLabelMesh& mesh, double voxel, std::size_t begin, std::size_t end, Scratch& s) {
  const Key cube = cubeOf(mesh, begin);
  if (!fanOf(mesh, begin, end, cube, s.fan)) return -1;
  const float* positions = mesh.positions.data();
  s.points.clear(), s.faces.clear();
  for (std::uint32_t v : s.fan.rim) s.points.push_back(at(positions, v)), s.faces.push_back(facesOf(mesh.keys[v], cube));
  if (!triangulateRim(s.points, s.faces, s.fan.rim, s.triangles)) return -1;
  Vec3 facing{0, 0, 0};  // the fan's area vector
  for (std::size_t t = begin; t < end; ++t) {
    const Vec3 a = at(positions, mesh.triangles[3 * t]);
    facing += glm::cross(at(positions, mesh.triangles[3 * t + 1]) - a, at(positions, mesh.triangles[3 * t + 2]) - a);
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(facing[a]) > std::abs(facing[axis])) axis = a;
  const int view = axis + (facing[axis] < 0 ? 3 : 0);
  const Vec3 inner = at(positions, s.fan.inner);
  double distance = INFINITY;
  for (std::size_t t = 0; t < s.triangles.size(); t += 3) {
    const Vec3 a = at(positions, s.triangles[t]), b = at(positions, s.triangles[t + 1]), c = at(positions, s.triangles[t + 2]);
    if (!(glm::dot(glm::cross(b - a, c - a), facing) > 0)) return -1;
    distance = std::min(distance, pointTriangleDistance(inner, a, b, c));
  }
  if (!(distance <= kTolerance * voxel)) return -1;
  return projectsOneToOne(positions, s.fan.rim.data(), s.fan.rim.size(), s.triangles.data(), view) ? view : -1;
}

// Where each cube's triangles start (cell order groups them), and the end; empty if the
// triangles are not in cell order.
std::vector<std::uint32_t> cubeRuns(const MultiLabelMesh& mesh, int threads) {
  const std::size_t count = mesh.triangleCount();
  std::vector<std::vector<std::uint32_t>> starts(static_cast<std::size_t>(chunkCount(count, threads)));
  std::vector<char> ordered(starts.size(), 1);
  parallelChunks(count, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    Key previous = begin == 0 ? 0 : cubeOf(mesh, begin - 1);
    for (std::size_t t = begin; t < end; ++t) {
      const Key cube = cubeOf(mesh, t);
      if (t > 0 && cube < previous) ordered[static_cast<std::size_t>(chunk)] = 0;  // keys order z, y, x as cells do
      if (t == 0 || cube != previous) starts[static_cast<std::size_t>(chunk)].push_back(static_cast<std::uint32_t>(t));
      previous = cube;
    }
  });
  std::vector<std::uint32_t> runs;
  for (std::size_t c = 0; c < starts.size(); ++c) {
    if (!ordered[c]) return {};
    runs.insert(runs.end(), starts[c].begin(), starts[c].end());
  }
  runs.push_back(static_cast<std::uint32_t>(count));
  return runs;
}

struct Plans {
  std::vector<std::int8_t> view;  // per run: its disk's view, -1: the fan stays
  std::vector<char> removed;      // per vertex
};

// Plans every cube in parallel, writing each one's new triangles over its first old ones (its
// rim, for the disk record, over the rest of its slots in `rims`).
Plans planCubes(MultiLabelMesh& mesh, double voxel, const std::vector<std::uint32_t>& runs, std::vector<std::uint32_t>& rims,
                int threads) {
  Plans plans{std::vector<std::int8_t>(runs.size() - 1, -1), std::vector<char>(mesh.vertexCount(), 0)};
  rims.assign(mesh.triangleCount(), 0);
  parallelChunks(runs.size() - 1, threads, [&](int, std::size_t first, std::size_t last) {
    Scratch s;
    for (std::size_t r = first; r < last; ++r) {
      const int view = planCube(mesh, voxel, runs[r], runs[r + 1], s);
      if (view < 0) continue;
      plans.view[r] = static_cast<std::int8_t>(view);
      plans.removed[s.fan.inner] = 1;  // no other cube holds it
      std::copy(s.triangles.begin(), s.triangles.end(), mesh.triangles.begin() + 3 * std::ptrdiff_t{runs[r]});
      std::copy(s.fan.rim.begin(), s.fan.rim.end(), rims.begin() + std::ptrdiff_t{runs[r]});
    }
  });
  return plans;
}

// Drops the removed vertices (keys stay in order) and the two last slots of every re-triangulated
// cube, renumbering; records the disks.
CubeDisks compact(MultiLabelMesh& mesh, std::vector<bool>& onSheet, const std::vector<std::uint32_t>& runs, const Plans& plans,
                  const std::vector<std::uint32_t>& rims) {
  std::vector<std::uint32_t> newIndex(mesh.vertexCount());
  std::uint32_t kept = 0;
  for (std::size_t v = 0; v < newIndex.size(); ++v) {
    newIndex[v] = kept;
    if (plans.removed[v]) continue;
    for (int a = 0; a < 3; ++a)
      mesh.positions[3 * kept + static_cast<std::uint32_t>(a)] = mesh.positions[3 * v + static_cast<std::size_t>(a)];
    mesh.keys[kept] = mesh.keys[v];
    if (v < onSheet.size()) onSheet[kept] = onSheet[v];
    ++kept;
  }
  mesh.positions.resize(3 * std::size_t{kept}), mesh.keys.resize(kept);
  if (onSheet.size() > kept) onSheet.resize(kept);
  CubeDisks disks;
  std::size_t out = 0;
  for (std::size_t r = 0; r + 1 < runs.size(); ++r) {
    const std::size_t size = runs[r + 1] - runs[r], keep = plans.view[r] < 0 ? size : size - 2;
    if (plans.view[r] >= 0) {
      disks.firstTriangle.push_back(static_cast<std::uint32_t>(out));
      disks.view.push_back(static_cast<std::uint8_t>(plans.view[r]));
      for (std::size_t i = 0; i < size; ++i) disks.rims.push_back(newIndex[rims[runs[r] + i]]);
      disks.rimStart.push_back(static_cast<std::uint32_t>(disks.rims.size()));
    }
    for (std::size_t t = runs[r]; t < runs[r] + keep; ++t, ++out) {
      for (int c = 0; c < 3; ++c)
        mesh.triangles[3 * out + static_cast<std::size_t>(c)] = newIndex[mesh.triangles[3 * t + static_cast<std::size_t>(c)]];
      mesh.labels[2 * out] = mesh.labels[2 * t], mesh.labels[2 * out + 1] = mesh.labels[2 * t + 1];
    }
  }
  mesh.triangles.resize(3 * out), mesh.labels.resize(2 * out);
  return disks;
}

bool diskEmbedded(const CubeDisks& disks, const MultiLabelMesh& mesh, std::size_t d) {
  const std::uint32_t* rim = &disks.rims[disks.rimStart[d]];
  const std::size_t n = disks.rimStart[d + 1] - disks.rimStart[d];
  return projectsOneToOne(mesh.positions.data(), rim, n, &mesh.triangles[3 * std::size_t{disks.firstTriangle[d]}], disks.view[d]);
}

}  // namespace

CubeDisks retriangulateCubeFans(MultiLabelMesh& mesh, const Grid& grid, std::vector<bool>& onSheet, int threads) {
  if (mesh.keys.size() != mesh.vertexCount() || mesh.triangleCount() == 0) return {};
  const std::vector<std::uint32_t> runs = cubeRuns(mesh, threads);
  if (runs.size() < 2) return {};
  std::vector<std::uint32_t> rims;
  const Plans plans = planCubes(mesh, std::min(grid.spacingX, grid.spacingY), runs, rims, threads);
  return compact(mesh, onSheet, runs, plans, rims);
}

bool disksEmbedded(const CubeDisks& disks, const MultiLabelMesh& mesh, int threads) {
  std::vector<char> ok(static_cast<std::size_t>(chunkCount(disks.count(), threads)), 1);
  parallelChunks(disks.count(), threads, [&](int chunk, std::size_t begin, std::size_t end) {
    for (std::size_t d = begin; d < end && ok[static_cast<std::size_t>(chunk)]; ++d)
      ok[static_cast<std::size_t>(chunk)] = diskEmbedded(disks, mesh, d);
  });
  return std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; });
}

std::size_t keepDisksEmbedded(const CubeDisks& disks, MultiLabelMesh& mesh, const std::vector<float>& before, int threads) {
  std::size_t putBack = 0;
  std::vector<char> folded(disks.count());
  for (;;) {
    parallelChunks(disks.count(), threads, [&](int, std::size_t begin, std::size_t end) {
      for (std::size_t d = begin; d < end; ++d) {
        bool moved = false;
        for (std::uint32_t i = disks.rimStart[d]; i < disks.rimStart[d + 1] && !moved; ++i)
          for (std::size_t a = 0; a < 3; ++a)
            moved = moved || mesh.positions[3 * std::size_t{disks.rims[i]} + a] != before[3 * std::size_t{disks.rims[i]} + a];
        folded[d] = moved && !diskEmbedded(disks, mesh, d);
      }
    });
    std::size_t round = 0;
    for (std::size_t d = 0; d < disks.count(); ++d)
      if (folded[d])
        for (std::uint32_t i = disks.rimStart[d]; i < disks.rimStart[d + 1]; ++i) {
          const std::size_t v = disks.rims[i];
          round += !std::equal(&before[3 * v], &before[3 * v] + 3, &mesh.positions[3 * v]);
          std::copy(&before[3 * v], &before[3 * v] + 3, &mesh.positions[3 * v]);
        }
    if (round == 0) return putBack;
    putBack += round;
  }
}

}  // namespace scansurf
