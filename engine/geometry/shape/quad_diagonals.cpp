// The better diagonal of each tetrahedron's surface quad. Why the surfaces still never
// cross (smoothing.cpp's argument): a (2+2) tetrahedron's quad joins points inside four of its
// edges, two on each face that its labels split; either diagonal joins points of the two
// remaining, opposite edges, so both triangulations lie in the tetrahedron and put the same
// segments on its faces. Two triangles sharing a diagonal meet only along it unless the quad is
// planar and the diagonal outside it, which folds one triangle back: refused, since both new
// triangles must face the way the old pair did.
#include "geometry/shape/quad_diagonals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "geometry/mesh/vec3.h"
#include "geometry/smoothing/edge_corners.h"

namespace scansurf {
namespace {

// Two lattice edges with no corner in common: in one tetrahedron, its opposite edges.
bool opposite(const EdgeCorners& e, const EdgeCorners& f) {
  return e.b != 0 && f.b != 0 && e.a != f.a && e.a != f.b && e.b != f.a && e.b != f.b;
}

// The edge of triangle t that is a quad's diagonal: its two vertices as (from, to) in t's
// winding; false if t has none (a 3+1 triangle, or one with a vertex off the lattice edges).
bool diagonalOf(const MultiLabelMesh& mesh, const std::vector<EdgeCorners>& carriers, std::size_t t, std::uint32_t edge[2]) {
  for (int c = 0; c < 3; ++c) {
    const std::uint32_t u = mesh.triangles[3 * t + c], w = mesh.triangles[3 * t + (c + 1) % 3];
    if (opposite(carriers[u], carriers[w])) {
      edge[0] = u, edge[1] = w;
      return true;
    }
  }
  return false;
}

Vec3 at(const MultiLabelMesh& m, std::uint32_t v) { return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}; }

// The cosine of the triangle's smallest angle: the larger, the sharper.
double sharpness(const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto cosine = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, w = r - p;
    return glm::dot(u, w) / std::sqrt(glm::dot(u, u) * glm::dot(w, w));
  };
  return std::max({cosine(a, b, c), cosine(b, c, a), cosine(c, a, b)});
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
  bool found = false;  // r1: the first triangle from the edge the second one shares, reversed
  for (int c = 0; c < 3 && !found; ++c)
    found = rotateTo(first, first[c], first[(c + 1) % 3], r1) && rotateTo(second, r1[1], r1[0], r2);
  if (!found) return false;
  const std::uint32_t ia = r1[0], ic = r1[1], ib = r1[2], id = r2[2];
  const Vec3 a = at(mesh, ia), b = at(mesh, ib), c = at(mesh, ic), d = at(mesh, id);
  const Vec3 facing = glm::cross(c - a, b - a) + glm::cross(a - c, d - c);
  const Vec3 m1 = glm::cross(d - a, b - a), m2 = glm::cross(c - d, b - d);
  if (!(glm::dot(m1, m2) > 0 && glm::dot(m1, facing) > 0 && glm::dot(m2, facing) > 0)) return false;
  const double before = std::max(sharpness(a, c, b), sharpness(c, a, d));
  const double after = std::max(sharpness(a, d, b), sharpness(d, c, b));
  if (!(after < before)) return false;
  const std::uint32_t n1[3] = {ia, id, ib}, n2[3] = {id, ic, ib};
  std::copy(n1, n1 + 3, first), std::copy(n2, n2 + 3, second);
  return true;
}

}  // namespace

// Assembly emits a quad's two triangles one after the other, and snapping keeps the order, so
// a quad is a triangle and the next one sharing its diagonal.
std::size_t chooseQuadDiagonals(MultiLabelMesh& mesh, int threads) {
  if (mesh.keys.size() != mesh.vertexCount() || mesh.triangleCount() < 2) return 0;
  const std::vector<EdgeCorners> carriers = edgeCornersOf(mesh, threads);
  const std::size_t pairs = mesh.triangleCount() - 1;
  std::vector<char> quadAt(pairs, 0);  // triangles t and t + 1 are one quad: read first, then flipped
  parallelChunks(pairs, threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      std::uint32_t first[2], second[2];
      quadAt[t] = diagonalOf(mesh, carriers, t, first) && diagonalOf(mesh, carriers, t + 1, second) && first[0] == second[1] &&
                  first[1] == second[0] && mesh.labels[2 * t] == mesh.labels[2 * t + 2] &&
                  mesh.labels[2 * t + 1] == mesh.labels[2 * t + 3];
    }
  });
  std::vector<std::size_t> flips(static_cast<std::size_t>(chunkCount(pairs, threads)), 0);
  parallelChunks(pairs, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
      if (quadAt[t])
        flips[static_cast<std::size_t>(chunk)] +=
            flipIfBetter(mesh, static_cast<std::uint32_t>(t), static_cast<std::uint32_t>(t + 1));
  });
  std::size_t total = 0;
  for (std::size_t f : flips) total += f;
  return total;
}

}  // namespace scansurf
