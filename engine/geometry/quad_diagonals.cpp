// The better diagonal of each tetrahedron's surface quad (issue 28). Why the surfaces still never
// cross (smoothing.cpp's argument): a (2+2) tetrahedron's quad joins points inside four of its
// edges, two on each face that its labels split; either diagonal joins points of the two
// remaining, opposite edges, so both triangulations lie in the tetrahedron and put the same
// segments on its faces. Two triangles sharing a diagonal meet only along it unless the quad is
// planar and the diagonal outside it, which folds one triangle back: refused, since both new
// triangles must face the way the old pair did.
#include "geometry/quad_diagonals.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "geometry/contour_fit.h"
#include "geometry/vec3.h"

namespace scansurf {
namespace {

using Corners = std::array<std::array<int, 3>, 2>;

// Per vertex: the two corners of its lattice edge, or a marker (count 0) off lattice edges.
struct EdgeCarrier {
  Corners corners{};
  bool onEdge = false;
};

std::vector<EdgeCarrier> edgeCarriers(const MultiLabelMesh& mesh, int threads) {
  std::vector<EdgeCarrier> out(mesh.vertexCount());
  parallelChunks(out.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const Carrier c = carrierOfKey(mesh.keys[v]);
      if (c.count != 2) continue;
      out[v].onEdge = true;
      for (int m = 0; m < 2; ++m) out[v].corners[m] = {c.corners[m][0], c.corners[m][1], c.corners[m][2]};
    }
  });
  return out;
}

// Two lattice edges with no corner in common: in one tetrahedron, its opposite edges.
bool opposite(const EdgeCarrier& a, const EdgeCarrier& b) {
  if (!a.onEdge || !b.onEdge) return false;
  for (const auto& p : a.corners)
    for (const auto& q : b.corners)
      if (p == q) return false;
  return true;
}

// Each quad diagonal as (edge, triangle): triangles of one quad share the edge's key.
std::vector<std::pair<std::uint64_t, std::uint32_t>> diagonals(const MultiLabelMesh& mesh,
                                                               const std::vector<EdgeCarrier>& carriers) {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> out;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t u = mesh.triangles[3 * t + c], w = mesh.triangles[3 * t + (c + 1) % 3];
      if (opposite(carriers[u], carriers[w]))
        out.emplace_back(std::uint64_t{std::min(u, w)} << 32 | std::max(u, w), static_cast<std::uint32_t>(t));
    }
  std::sort(out.begin(), out.end());
  return out;
}

Vec3 at(const MultiLabelMesh& m, std::uint32_t v) { return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}; }

double smallestAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, w = r - p;
    return std::atan2(glm::length(glm::cross(u, w)), glm::dot(u, w));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

// Rotates triangle t so that its first edge runs from `from` to `to`; false if it has no such edge.
bool rotateTo(const std::uint32_t* tri, std::uint32_t from, std::uint32_t to, std::uint32_t out[3]) {
  for (int c = 0; c < 3; ++c)
    if (tri[c] == from && tri[(c + 1) % 3] == to) {
      for (int k = 0; k < 3; ++k) out[k] = tri[(c + k) % 3];
      return true;
    }
  return false;
}

// Triangles (a, c, b) and (c, a, d) of one quad a-d-c-b: re-split along d-b where that is better.
bool flipIfBetter(MultiLabelMesh& mesh, std::uint32_t t1, std::uint32_t t2) {
  std::uint32_t* first = &mesh.triangles[3 * std::size_t{t1}];
  std::uint32_t* second = &mesh.triangles[3 * std::size_t{t2}];
  std::uint32_t r1[3], r2[3];
  bool found = false;
  for (int c = 0; c < 3 && !found; ++c) {
    found = rotateTo(first, first[c], first[(c + 1) % 3], r1) && rotateTo(second, r1[1], r1[0], r2);
  }
  if (!found) return false;
  const std::uint32_t ia = r1[0], ic = r1[1], ib = r1[2], id = r2[2];
  const Vec3 a = at(mesh, ia), b = at(mesh, ib), c = at(mesh, ic), d = at(mesh, id);
  const Vec3 facing = glm::cross(c - a, b - a) + glm::cross(a - c, d - c);
  const Vec3 m1 = glm::cross(d - a, b - a), m2 = glm::cross(c - d, b - d);
  if (!(glm::dot(m1, m2) > 0 && glm::dot(m1, facing) > 0 && glm::dot(m2, facing) > 0)) return false;
  const double before = std::min(smallestAngle(a, c, b), smallestAngle(c, a, d));
  const double after = std::min(smallestAngle(a, d, b), smallestAngle(d, c, b));
  if (!(after > before)) return false;
  const std::uint32_t n1[3] = {ia, id, ib}, n2[3] = {id, ic, ib};
  std::copy(n1, n1 + 3, first), std::copy(n2, n2 + 3, second);
  return true;
}

}  // namespace

std::size_t chooseQuadDiagonals(MultiLabelMesh& mesh, int threads) {
  if (mesh.keys.size() != mesh.vertexCount()) return 0;
  const std::vector<EdgeCarrier> carriers = edgeCarriers(mesh, threads);
  const auto diagonal = diagonals(mesh, carriers);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> quads;
  for (std::size_t i = 0; i + 1 < diagonal.size(); ++i)
    if (diagonal[i].first == diagonal[i + 1].first && (i + 2 == diagonal.size() || diagonal[i + 2].first != diagonal[i].first) &&
        (i == 0 || diagonal[i - 1].first != diagonal[i].first) &&
        mesh.labels[2 * diagonal[i].second] == mesh.labels[2 * diagonal[i + 1].second] &&
        mesh.labels[2 * diagonal[i].second + 1] == mesh.labels[2 * diagonal[i + 1].second + 1])
      quads.emplace_back(diagonal[i].second, diagonal[i + 1].second);
  std::vector<std::size_t> flips(static_cast<std::size_t>(chunkCount(quads.size(), threads)), 0);
  parallelChunks(quads.size(), threads, [&](int chunk, std::size_t begin, std::size_t end) {
    for (std::size_t q = begin; q < end; ++q)
      flips[static_cast<std::size_t>(chunk)] += flipIfBetter(mesh, quads[q].first, quads[q].second);
  });
  std::size_t total = 0;
  for (std::size_t f : flips) total += f;
  return total;
}

}  // namespace scansurf
