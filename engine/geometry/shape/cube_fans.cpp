// Re-triangulating the cubes' fans. In a cube whose separating surface carries two
// labels, the Freudenthal cut puts a vertex on each cut cube edge and face diagonal and one on
// the body diagonal, and fans the surface around that last one; marching cubes (Lorensen &
// Cline 1987) triangulates the same rim with no inner vertex. Where the surface is flat over a
// box of 2 x 2 x 2, 2 x 2 x 1 or 1 x 1 x 2 cubes, the vertices on the box's inner faces and
// edges go too (passes in that order, the 2-thick ones at both parities of z; then single cubes).
//
// Why the surfaces still never cross. A region is a box. Its disk's rim lies on the box's faces
// (on cube edges, face diagonals or voxel centres) and no new edge joins two vertices of one
// face, so every new triangle but its rim edges lies in the open box, where no other region's
// triangle is (each lies in its own closed tetrahedron or box); the rim edges are the ones the
// surface had, shared with the neighbouring regions. Inside the box the new triangles are the
// only ones (the box carried one disk), and they cannot meet each other: each projects along
// the disk's axis with the same orientation (exact), and so does the rim, one-to-one, so the
// projection maps the disk onto the rim's inside one-to-one (a locally one-to-one map of a disk
// with a simple boundary curve is). The disk has the old rim, so it splits the box's voxel
// centres on its faces as the old surface did: the labels on either side stay; the vertices
// removed were inside the box, on no other region's triangle.
//
// Why the contour planes stay. A box two layers thick has a lattice layer inside (a contour
// plane or one between); its disk's cut there becomes the chord between the rim's two vertices
// on the layer: no new triangle reaches from one side of the layer to the other, so the layer
// cuts the new disk along that edge alone, and every removed vertex on the layer lies within
// 0.05 of the box's finest lattice spacing of it (so the cross-section moves no further). The
// old cut lies within that distance too, so a 2 x 2 x 2 box's one inner voxel centre, if
// further, keeps its side; nearer, the box is left.
#include "geometry/shape/cube_fans.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "core/parallel.h"
#include "geometry/extraction/assembly.h"
#include "geometry/mesh/triangle_intersection.h"
#include "geometry/mesh/vec3.h"
#include "geometry/smoothing/carrier_projection.h"

namespace scansurf {
namespace {

constexpr double kTolerance = 0.05;         // of the box's finest spacing: how far a removed vertex may lie from the new disk
constexpr std::size_t kLongestRim = 32;     // a longer rim keeps its triangles
constexpr std::size_t kMostTriangles = 96;  // so does a region with more triangles
constexpr std::size_t kMostVertices = kMostTriangles + 1;  // a disk has at most F + 1 vertices
constexpr std::uint32_t kDead = UINT32_MAX;                // a triangle slot left empty
// A new triangle may be sharper than the sharpest it replaces only if its smallest angle is at
// least 15 degrees (the smallest angle the triangle shape aims at): sharpness(), its squared cosine, at most this.
constexpr double kFair = 0.9330127018922194;

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

// A box of `size` x `size` x `height` cubes whose lowest voxel centre is `low` (voxel indices).
struct Box {
  std::array<std::uint64_t, 3> low{};
  std::uint64_t size = 1, height = 1;

  // A box two layers thick has a layer inside: its key along z (0 if none).
  std::uint64_t middle() const { return height == 2 ? 12 * (low[2] + 1) : 0; }
};

// Bit 2a (2a + 1): the key lies on the box's low (high) face across axis a; 0: inside.
int facesOf(Key key, const Box& box) {
  const auto k = unpack(key);
  int mask = 0;
  for (int a = 0; a < 3; ++a) {
    const std::uint64_t low = 12 * box.low[a], high = low + 12 * (a < 2 ? box.size : box.height);
    mask |= (k[a] == low ? 1 : 0) << (2 * a) | (k[a] == high ? 2 : 0) << (2 * a);
  }
  return mask;
}

// The squared cosine of a triangle's smallest angle (opposite its shortest side; at most 60
// degrees, so its cosine is positive) from its sides' squares: the smaller, the better shaped.
double sharpness(double ab, double bc, double ca) {
  const double shortest = std::min({ab, bc, ca});
  if (!(shortest > 0)) return 1;
  const double twiceProduct = ab + bc + ca - 2 * shortest;  // b^2 + c^2 - a^2 = 2 b c cos
  return twiceProduct * twiceProduct * shortest / (4 * ab * bc * ca);
}

double pointSegmentDistance(const Vec3& p, const Vec3& s, const Vec3& e) {
  const Vec3 d = e - s;
  const double t = std::clamp(glm::dot(p - s, d) / std::max(glm::dot(d, d), 1e-300), 0.0, 1.0);
  return glm::length(p - (s + d * t));
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
  return std::min({pointSegmentDistance(p, a, b), pointSegmentDistance(p, b, c), pointSegmentDistance(p, c, a)});
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

// A region's triangles as one disk: its rim in their orientation and the vertices inside.
struct Disk {
  std::vector<std::uint32_t> rim, inner;
};

// Local indices of a region's vertices (at most kMostVertices), and its directed edges: for edge
// a -> b, the third corner of its triangle (that is, a's link steps from b to it).
struct LocalMesh {
  std::array<std::uint32_t, kMostVertices> ids;
  std::array<std::uint8_t, kMostVertices * kMostVertices> thirds;   // third corner + 1; 0: no edge a -> b
  std::array<std::uint8_t, kMostVertices> incident, anyOut;         // per vertex: triangles, one edge out
  std::array<std::array<std::uint8_t, 3>, kMostTriangles> corners;  // per triangle, local indices
  std::size_t vertices = 0;
  // Open addressing from vertex id to local index + 1 (0: empty): a region meets each of its
  // vertices about six times, and a linear search over ids cost more than the rest of reading.
  static constexpr std::size_t kSlots = 256;  // a power of two, over twice kMostVertices
  std::array<std::uint32_t, kSlots> slotIds;
  std::array<std::uint8_t, kSlots> slotLocal;

  std::uint8_t& third(std::size_t a, std::size_t b) { return thirds[a * kMostVertices + b]; }
  // The local index of v, added if new; kMostVertices if full.
  std::size_t local(std::uint32_t v) {
    std::size_t slot = (v * 2654435761u) >> 24;  // Knuth's multiplicative hash, top 8 of 32 bits
    for (; slotLocal[slot] != 0; slot = (slot + 1) & (kSlots - 1))
      if (slotIds[slot] == v) return slotLocal[slot] - 1u;
    if (vertices == kMostVertices) return kMostVertices;
    slotIds[slot] = v, slotLocal[slot] = static_cast<std::uint8_t>(vertices + 1);
    ids[vertices] = v;
    return vertices++;
  }
  // Reads the region's triangles; false if one label pair does not hold them all, a directed
  // edge is used twice (no manifold) or there are too many vertices.
  bool read(const MultiLabelMesh& mesh, const std::vector<std::uint32_t>& triangles) {
    const std::size_t first = triangles.front();
    vertices = 0;
    slotLocal.fill(0);
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      const std::size_t t = triangles[i];
      if (mesh.labels[2 * t] != mesh.labels[2 * first] || mesh.labels[2 * t + 1] != mesh.labels[2 * first + 1]) return false;
      for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t a = local(mesh.triangles[3 * t + k]);
        if (a == kMostVertices) return false;
        corners[i][k] = static_cast<std::uint8_t>(a);
      }
    }
    std::fill_n(thirds.begin(), vertices * kMostVertices, std::uint8_t{0});
    std::fill_n(incident.begin(), vertices, std::uint8_t{0});
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      const std::array<std::uint8_t, 3>& c = corners[i];
      for (std::size_t k = 0; k < 3; ++k) {
        std::uint8_t& t3 = third(c[k], c[(k + 1) % 3]);
        if (t3 != 0) return false;
        t3 = static_cast<std::uint8_t>(c[(k + 2) % 3] + 1);
        ++incident[c[k]], anyOut[c[k]] = c[(k + 1) % 3];
      }
    }
    return true;
  }
};

// Whether vertex a's link (the far edge of each of its triangles) is one path (from the end of
// its rim edge out, `start`) or one cycle, so that its triangles form one fan.
bool oneFan(LocalMesh& m, std::size_t a, std::size_t start) {
  std::size_t walked = 0;
  for (std::size_t b = start; m.third(a, b) != 0 && walked <= m.incident[a];) {
    ++walked;
    if ((b = m.third(a, b) - 1u) == start) break;
  }
  return walked == m.incident[a];
}

// The region's triangles as one disk whose rim lies on the box's faces and whose other vertices
// all lie inside the box: one label pair, every edge used once each way at most, one rim cycle,
// one fan at every vertex, connected, Euler characteristic 1.
bool diskOf(const MultiLabelMesh& mesh, const std::vector<std::uint32_t>& triangles, const Box& box, LocalMesh& m, Disk& disk) {
  if (triangles.size() < 3 || triangles.size() > kMostTriangles || !m.read(mesh, triangles)) return false;
  std::array<std::uint8_t, kMostVertices> next, parent;
  next.fill(0xff);
  std::iota(parent.begin(), parent.end(), std::uint8_t{0});
  const auto root = [&](std::size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::size_t rimEdges = 0, components = m.vertices;
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t a = m.corners[i][k], b = m.corners[i][(k + 1) % 3];
      if (const std::size_t ra = root(a), rb = root(b); ra != rb) parent[ra] = static_cast<std::uint8_t>(rb), --components;
      if (m.third(b, a)) continue;
      if (next[a] != 0xff) return false;  // two rim edges leave a: a pinch
      next[a] = static_cast<std::uint8_t>(b), ++rimEdges;
    }
  const std::size_t edges = (3 * triangles.size() + rimEdges) / 2;
  if (components != 1 || m.vertices + triangles.size() != edges + 1 || rimEdges < 3 || rimEdges > kLongestRim) return false;
  std::size_t start = 0;
  while (next[start] == 0xff) ++start;
  disk.rim.clear(), disk.inner.clear();
  for (std::size_t a = start; disk.rim.size() < rimEdges;) {  // one cycle through every rim edge
    disk.rim.push_back(m.ids[a]);
    if (next[a] == 0xff || facesOf(mesh.keys[m.ids[a]], box) == 0) return false;
    a = next[a];
    if (a == start) break;
  }
  if (disk.rim.size() != rimEdges) return false;
  for (std::size_t a = 0; a < m.vertices; ++a) {
    const bool onRim = next[a] != 0xff;
    if (!oneFan(m, a, onRim ? next[a] : m.anyOut[a])) return false;
    if (!onRim) {
      if (facesOf(mesh.keys[m.ids[a]], box) != 0) return false;
      disk.inner.push_back(m.ids[a]);
    }
  }
  return !disk.inner.empty();
}

// The rim's triangulation with the largest smallest angle, no edge between two vertices on one
// face of the box and none from one side of its middle layer to the other (`sides`: -1 below, 0
// on, 1 above; all 1 in a box one layer thick), by dynamic programming over sub-polygons; false
// if there is none with every triangle's sharpness at most `bound`. A sub-polygon sharper than
// the bound can only make sharper ones, so it counts as none: the same answer, fewer triangles
// weighed (most regions that keep their triangles are refused here).
bool triangulateRim(const std::vector<Vec3>& p, const std::vector<int>& faces, const std::vector<int>& sides,
                    const std::vector<std::uint32_t>& rim, double bound, std::vector<std::uint32_t>& out) {
  const std::size_t n = p.size();
  if (n == 3 && (faces[0] & faces[1] & faces[2])) return false;  // a triangle in one face
  std::array<double, kLongestRim * kLongestRim> square;          // squared distances between rim vertices
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) square[i * n + j] = glm::dot(p[j] - p[i], p[j] - p[i]);
  const auto allowed = [&](std::size_t i, std::size_t j) {
    return j - i == 1 || (i == 0 && j == n - 1) || (!(faces[i] & faces[j]) && sides[i] * sides[j] >= 0);
  };
  std::array<double, kLongestRim * kLongestRim> worst;  // of sub-polygon i..j: its sharpest triangle's sharpness
  std::array<std::uint8_t, kLongestRim * kLongestRim> split;
  std::fill_n(worst.begin(), n * n, 2.0);  // 2: no triangulation (only the first n * n entries are used)
  for (std::size_t i = 0; i + 1 < n; ++i) worst[i * n + i + 1] = -1;  // an edge: no triangle yet
  for (std::size_t length = 2; length < n; ++length)
    for (std::size_t i = 0; i + length < n; ++i) {
      const std::size_t j = i + length;
      if (!allowed(i, j)) continue;
      double& best = worst[i * n + j];
      for (std::size_t k = i + 1; k < j; ++k) {
        const double parts = std::max(worst[i * n + k], worst[k * n + j]);
        if (parts >= best) continue;  // no better than the best so far, or a part has none
        const double q = std::max(parts, sharpness(square[i * n + k], square[k * n + j], square[i * n + j]));
        if (q < best && q <= bound) best = q, split[i * n + j] = static_cast<std::uint8_t>(k);
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
  LocalMesh local;
  Disk disk;
  std::vector<Vec3> points;
  std::vector<int> faces, sides;
  std::vector<std::uint32_t> triangles;
};

// The side of a box's middle layer a key lies on: -1 below, 0 on, 1 above (1 if no middle).
int sideOf(Key key, const Box& box) {
  const std::uint64_t z = unpack(key)[2], middle = box.middle();
  return middle == 0 || z > middle ? 1 : z < middle ? -1 : 0;
}

// In a box two layers thick, the disk's cut by the middle layer becomes the chord between its two
// rim vertices there: true if it has two, each removed vertex on the layer lies within
// `tolerance` of the chord (so the cross-section moves no further), and the new triangles keep
// to either side (triangulateRim), so the layer cuts them along the chord only. The old cut lies
// within `tolerance` of the chord too (its vertices do, and so their segments), so a voxel
// centre further from the chord keeps its side: a block's one inner centre must be.
// Read off the region's triangles before diskOf: of a disk, the rim vertices are exactly those
// on the box's faces, and about 40 % of these boxes' regions stop here, cheaper than at diskOf.
bool chordKeepsCrossSection(const MultiLabelMesh& mesh, const Grid& grid, const Box& box,
                            const std::vector<std::uint32_t>& region, double tolerance) {
  const std::uint64_t middle = box.middle();
  if (middle == 0) return true;
  std::array<std::uint32_t, kMostVertices> ends, inner;  // the layer's vertices on the faces, inside
  std::size_t endCount = 0, innerCount = 0;
  for (std::uint32_t t : region)
    for (std::size_t c = 0; c < 3; ++c) {
      const std::uint32_t v = mesh.triangles[3 * std::size_t{t} + c];
      if (unpack(mesh.keys[v])[2] != middle) continue;
      const bool onFace = facesOf(mesh.keys[v], box) != 0;
      auto& list = onFace ? ends : inner;
      std::size_t& count = onFace ? endCount : innerCount;
      if (std::find(list.begin(), list.begin() + count, v) != list.begin() + count) continue;
      if (count == list.size()) return false;  // more vertices than a disk of this size has
      list[count++] = v;
      if (endCount > 2) return false;
    }
  if (endCount != 2) return false;
  const float* positions = mesh.positions.data();
  const Vec3 a = at(positions, ends[0]), b = at(positions, ends[1]);
  if (box.size == 2) {  // the inner voxel centre, on the layer
    const int centre[3] = {static_cast<int>(box.low[0] + 1), static_cast<int>(box.low[1] + 1), static_cast<int>(box.low[2] + 1)};
    if (!(pointSegmentDistance(cornerPosition(grid, centre), a, b) > tolerance)) return false;
  }
  for (std::size_t i = 0; i < innerCount; ++i)
    if (pointSegmentDistance(at(positions, inner[i]), a, b) > tolerance) return false;
  return true;
}

// The box's finest lattice spacing: the pixel, or a layer gap inside it where the layers lie
// closer (slices thinner than the pixels), so that the tolerance is a share of the lattice there.
double finestSpacing(const Grid& grid, const Box& box) {
  double finest = std::min(grid.spacingX, grid.spacingY);
  // A box of two layers may reach past the top layer; no surface lies beyond it.
  const std::uint64_t top = std::min<std::uint64_t>(box.low[2] + box.height, grid.layerZ.size() - 1);
  for (std::uint64_t k = box.low[2]; k < top; ++k) finest = std::min(finest, grid.layerZ[k + 1] - grid.layerZ[k]);
  return finest;
}

// Plans a region (its triangles, in slot order): on success its new triangles are in
// s.triangles and its view returned (else -1).
int planRegion(const MultiLabelMesh& mesh, const Grid& grid, const std::vector<std::uint32_t>& region, const Box& box,
               Scratch& s) {
  const double tolerance = kTolerance * finestSpacing(grid, box);
  if (!chordKeepsCrossSection(mesh, grid, box, region, tolerance) || !diskOf(mesh, region, box, s.local, s.disk)) return -1;
  const float* positions = mesh.positions.data();
  s.points.clear(), s.faces.clear(), s.sides.clear();
  for (std::uint32_t v : s.disk.rim) {
    s.points.push_back(at(positions, v)), s.faces.push_back(facesOf(mesh.keys[v], box));
    s.sides.push_back(sideOf(mesh.keys[v], box));
  }
  Vec3 facing{0, 0, 0};  // the old disk's area vector
  double sharpestBefore = -1;
  for (std::uint32_t t : region) {
    const Vec3 a = at(positions, mesh.triangles[3 * t]), b = at(positions, mesh.triangles[3 * t + 1]),
               c = at(positions, mesh.triangles[3 * t + 2]);
    facing += glm::cross(b - a, c - a);
    sharpestBefore = std::max(sharpestBefore, sharpness(glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)));
  }
  if (!triangulateRim(s.points, s.faces, s.sides, s.disk.rim, std::max(sharpestBefore, kFair), s.triangles)) return -1;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(facing[a]) > std::abs(facing[axis])) axis = a;
  const int view = axis + (facing[axis] < 0 ? 3 : 0);
  for (std::size_t t = 0; t < s.triangles.size(); t += 3) {
    const Vec3 a = at(positions, s.triangles[t]), b = at(positions, s.triangles[t + 1]), c = at(positions, s.triangles[t + 2]);
    if (!(glm::dot(glm::cross(b - a, c - a), facing) > 0)) return -1;
  }
  for (std::uint32_t v : s.disk.inner) {  // each removed vertex near some new triangle
    bool near = false;
    for (std::size_t t = 0; t < s.triangles.size() && !near; t += 3)
      near = pointTriangleDistance(at(positions, v), at(positions, s.triangles[t]), at(positions, s.triangles[t + 1]),
                                   at(positions, s.triangles[t + 2])) <= tolerance;
    if (!near) return -1;
  }
  return projectsOneToOne(positions, s.disk.rim.data(), s.disk.rim.size(), s.triangles.data(), view) ? view : -1;
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

// Regions to try, each a list of runs (from cubeRuns): region i's are runs[start[i]..start[i+1]).
struct Regions {
  std::vector<std::uint32_t> start{0}, runs;
  std::size_t count() const { return start.size() - 1; }
};

// Every cube alone.
Regions cubesOf(std::size_t runCount) {
  Regions out{std::vector<std::uint32_t>(runCount + 1), std::vector<std::uint32_t>(runCount)};
  std::iota(out.start.begin(), out.start.end(), 0u), std::iota(out.runs.begin(), out.runs.end(), 0u);
  return out;
}

// The boxes a pass tries: `size` x `size` x `height` cubes, at voxel indices that are multiples
// of the size in x and y and, less `offset`, of the height in z.
struct BoxShape {
  std::uint64_t size = 1, height = 1, offset = 0;

  std::uint64_t cubes() const { return size * size * height; }
  std::array<std::uint64_t, 3> blockOf(const std::array<std::uint64_t, 3>& cube) const {
    return {cube[0] / size, cube[1] / size, (cube[2] + offset) / height};
  }
  // The box holding a cube; false where it would reach below the volume.
  bool boxOf(const std::array<std::uint64_t, 3>& cube, Box& box) const {
    const auto b = blockOf(cube);
    if (b[2] * height < offset) return false;
    box = {{b[0] * size, b[1] * size, b[2] * height - offset}, size, height};
    return true;
  }
};

// Every block of the shape's boxes with its cubes' runs, in key order. The cubes come in key
// order (z, y, x), so a layer of blocks is a run of them: the layers sort apart, in parallel.
Regions blocksOf(const std::vector<Key>& cubes, const BoxShape& shape, int threads) {
  std::vector<std::pair<Key, std::uint32_t>> byBlock(cubes.size());
  std::vector<std::size_t> layerStart;  // where each layer of blocks starts in byBlock
  for (std::size_t r = 0; r < cubes.size(); ++r) {
    const auto b = shape.blockOf(unpack(cubes[r]));
    byBlock[r] = {packVertexKey(b[0], b[1], b[2]), static_cast<std::uint32_t>(r)};
    if (r == 0 || unpack(byBlock[r].first)[2] != unpack(byBlock[r - 1].first)[2]) layerStart.push_back(r);
  }
  layerStart.push_back(cubes.size());
  parallelChunks(layerStart.size() - 1, threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t l = begin; l < end; ++l) std::sort(byBlock.begin() + layerStart[l], byBlock.begin() + layerStart[l + 1]);
  });
  Regions out;
  out.runs.reserve(byBlock.size());
  for (std::size_t i = 0; i < byBlock.size(); ++i) {
    if (i > 0 && byBlock[i].first != byBlock[i - 1].first) out.start.push_back(static_cast<std::uint32_t>(i));
    out.runs.push_back(byBlock[i].second);
  }
  out.start.push_back(static_cast<std::uint32_t>(byBlock.size()));
  return out;
}

// The regions re-triangulated: each one's rim, the slots its new triangles went to, its view.
struct Planned {
  std::vector<std::uint32_t> rimStart{0}, rims, slotStart{0}, slots;
  std::vector<std::uint8_t> views;

  void add(const std::vector<std::uint32_t>& rim, const std::uint32_t* slotsUsed, std::size_t count, int view) {
    rims.insert(rims.end(), rim.begin(), rim.end()), slots.insert(slots.end(), slotsUsed, slotsUsed + count);
    rimStart.push_back(static_cast<std::uint32_t>(rims.size())), slotStart.push_back(static_cast<std::uint32_t>(slots.size()));
    views.push_back(static_cast<std::uint8_t>(view));
  }
};

// Plans each region whose runs are all free, in parallel; a planned region's new triangles go
// over its first slots, its other slots die, its runs are taken and its inner vertices removed.
// Results in region order.
void planRegions(MultiLabelMesh& mesh, const Grid& grid, const std::vector<std::uint32_t>& runs, const std::vector<Key>& cubes,
                 const Regions& regions, const BoxShape& shape, std::vector<char>& taken, std::vector<char>& removed,
                 Planned& out, int threads) {
  std::vector<Planned> perChunk(static_cast<std::size_t>(chunkCount(regions.count(), threads)));
  parallelChunks(regions.count(), threads, [&](int chunk, std::size_t first, std::size_t last) {
    Scratch s;
    std::vector<std::uint32_t> slots;
    for (std::size_t i = first; i < last; ++i) {
      slots.clear();
      bool free = true;
      for (std::uint32_t k = regions.start[i]; k < regions.start[i + 1]; ++k) {
        const std::uint32_t r = regions.runs[k];
        free = free && !taken[r];
        for (std::uint32_t t = runs[r]; t < runs[r + 1]; ++t) slots.push_back(t);
      }
      if (!free || slots.size() > kMostTriangles) continue;
      if (shape.cubes() > 1 && regions.start[i + 1] - regions.start[i] < 2) continue;  // a block of one cube: its cube's turn
      Box box;
      if (!shape.boxOf(unpack(cubes[regions.runs[regions.start[i]]]), box)) continue;
      const int view = planRegion(mesh, grid, slots, box, s);
      if (view < 0) continue;
      for (std::uint32_t k = regions.start[i]; k < regions.start[i + 1]; ++k) taken[regions.runs[k]] = 1;
      for (std::uint32_t v : s.disk.inner) removed[v] = 1;  // no other region holds it
      const std::size_t kept = s.triangles.size() / 3;
      for (std::size_t k = 0; k < slots.size(); ++k) {
        std::uint32_t* tri = &mesh.triangles[3 * std::size_t{slots[k]}];
        if (k < kept)
          std::copy(&s.triangles[3 * k], &s.triangles[3 * k] + 3, tri);
        else
          tri[0] = kDead;
      }
      perChunk[static_cast<std::size_t>(chunk)].add(s.disk.rim, slots.data(), kept, view);
    }
  });
  for (const Planned& c : perChunk)
    for (std::size_t d = 0; d + 1 < c.rimStart.size(); ++d)
      out.add({c.rims.begin() + c.rimStart[d], c.rims.begin() + c.rimStart[d + 1]}, &c.slots[c.slotStart[d]],
              c.slotStart[d + 1] - c.slotStart[d], c.views[d]);
}

// Drops the removed vertices (keys stay in order) and the dead slots, renumbering; records the
// disks.
CubeDisks compact(MultiLabelMesh& mesh, std::vector<bool>& onSheet, const std::vector<char>& removed, const Planned& planned) {
  std::vector<std::uint32_t> newIndex(mesh.vertexCount());
  std::uint32_t kept = 0;
  for (std::size_t v = 0; v < newIndex.size(); ++v) {
    newIndex[v] = kept;
    if (removed[v]) continue;
    for (std::size_t a = 0; a < 3; ++a) mesh.positions[3 * std::size_t{kept} + a] = mesh.positions[3 * v + a];
    mesh.keys[kept] = mesh.keys[v];
    if (v < onSheet.size()) onSheet[kept] = onSheet[v];
    ++kept;
  }
  mesh.positions.resize(3 * std::size_t{kept}), mesh.keys.resize(kept);
  if (onSheet.size() > kept) onSheet.resize(kept);
  std::vector<std::uint32_t> newSlot(mesh.triangleCount());
  std::size_t out = 0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    newSlot[t] = static_cast<std::uint32_t>(out);
    if (mesh.triangles[3 * t] == kDead) continue;
    for (std::size_t c = 0; c < 3; ++c) mesh.triangles[3 * out + c] = newIndex[mesh.triangles[3 * t + c]];
    mesh.labels[2 * out] = mesh.labels[2 * t], mesh.labels[2 * out + 1] = mesh.labels[2 * t + 1];
    ++out;
  }
  mesh.triangles.resize(3 * out), mesh.labels.resize(2 * out);
  CubeDisks disks;
  disks.rimStart = planned.rimStart, disks.triangleStart = planned.slotStart, disks.view = planned.views;
  disks.rims.resize(planned.rims.size()), disks.triangles.resize(planned.slots.size());
  for (std::size_t i = 0; i < planned.rims.size(); ++i) disks.rims[i] = newIndex[planned.rims[i]];
  for (std::size_t i = 0; i < planned.slots.size(); ++i) disks.triangles[i] = newSlot[planned.slots[i]];
  return disks;
}

bool diskEmbedded(const CubeDisks& disks, const MultiLabelMesh& mesh, std::size_t d) {
  std::array<std::uint32_t, 3 * kLongestRim> triangles;
  std::size_t k = 0;
  for (std::uint32_t i = disks.triangleStart[d]; i < disks.triangleStart[d + 1]; ++i)
    for (std::size_t c = 0; c < 3; ++c) triangles[k++] = mesh.triangles[3 * std::size_t{disks.triangles[i]} + c];
  return projectsOneToOne(mesh.positions.data(), &disks.rims[disks.rimStart[d]], disks.rimStart[d + 1] - disks.rimStart[d],
                          triangles.data(), disks.view[d]);
}

}  // namespace

CubeDisks retriangulateCubeFans(MultiLabelMesh& mesh, const Grid& grid, std::vector<bool>& onSheet, int threads) {
  if (mesh.keys.size() != mesh.vertexCount() || mesh.triangleCount() == 0) return {};
  const std::vector<std::uint32_t> runs = cubeRuns(mesh, threads);
  if (runs.size() < 2) return {};
  std::vector<char> taken(runs.size() - 1, 0), removed(mesh.vertexCount(), 0);
  Planned planned;
  std::vector<Key> cubes(runs.size() - 1);  // each run's cube, read before any pass rewrites its triangles
  for (std::size_t r = 0; r < cubes.size(); ++r) cubes[r] = cubeOf(mesh, runs[r]);
  for (const BoxShape shape : {BoxShape{2, 2, 0}, BoxShape{2, 2, 1}, BoxShape{2, 1, 0}, BoxShape{1, 2, 0}, BoxShape{1, 2, 1}})
    planRegions(mesh, grid, runs, cubes, blocksOf(cubes, shape, threads), shape, taken, removed, planned, threads);
  planRegions(mesh, grid, runs, cubes, cubesOf(cubes.size()), BoxShape{}, taken, removed, planned, threads);
  CubeDisks disks = compact(mesh, onSheet, removed, planned);
  disks.removedVertices = static_cast<std::size_t>(std::count(removed.begin(), removed.end(), 1));
  return disks;
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
