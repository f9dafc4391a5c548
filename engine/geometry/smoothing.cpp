// Constrained smoothing of separating surfaces (Lee, Fletcher, Whitaker et al., "Scanline
// Surfacing", §3.5; after Whitaker, "Reducing aliasing artifacts in iso-surfaces of binary
// volumes", 2000, and Gibson's constrained elastic surface nets, 1998).
//
// The paper confines each vertex to an ellipsoid around its original position, the
// ellipsoids packed without overlap. We take the tightest region that provably keeps the
// surfaces apart: every vertex of the separating surface is the barycentre of a simplex of
// the grid's Freudenthal tetrahedra (an edge, a face or a tetrahedron whose corners are voxel
// centres; its "carrier", recovered exactly from the vertex's integer key), and it may move
// anywhere strictly inside that simplex (barycentric weights >= kMargin). These regions never
// overlap (the open simplices of a triangulation are disjoint) and are anisotropic exactly as
// the voxels are. Why no two triangles can then cross: every triangle of a tetrahedron T has
// its vertices in simplices of T, so it stays inside T, and two triangles of different
// tetrahedra can meet only on their common face, where both sides use the same face curve.
// Inside T, with two labels the triangle (3+1) or the quad split along a diagonal (2+2)
// joins points interior to distinct edges, a convex section or two triangles either side of
// an interior diagonal; with three or more labels the face curves are segments from edge
// points to one interior face point, which cannot cross, and the triangles are their cone
// from a point interior to T, each ray of which leaves T once, so cones meet only along
// common rays. Hence any positions inside the carriers give an embedded mesh with the same
// combinatorics: closed, oriented, same genus, abutting surfaces sharing every vertex.
//
// Relaxation: a vertex's neighbours are its edge neighbours on its sheet; a vertex on a
// junction curve (an edge there has triangles of more than one label pair) uses its two curve
// neighbours, and where curves meet the vertex stays. Each sweep is bi-Laplacian fairing
// (umbrella of umbrellas, Kobbelt et al. 1998) plus a little Laplacian tension, with Jacobi
// updates: unlike Laplacian or Taubin smoothing between pinned rings, fairing carries the
// curvature across the contour rings, so it neither shrinks the shape toward the chords nor
// flattens the caps beyond the last contours. A sheet vertex then slides along its carrier
// edge to where the target's tangent plane cuts it (tangential drift would otherwise turn into
// normal error on slanted edges); junction vertices take the nearest point of their carrier.
// Vertices fitted to the contours (geometry/contour_fit.h) stay.
#include "geometry/smoothing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "geometry/contour_fit.h"

namespace scansurf {
namespace {

constexpr double kMargin = 0.02;  // least barycentric weight inside a carrier
constexpr double kBending = 0.45;  // bi-Laplacian step at strength 1
constexpr double kTension = 0.0875;  // Laplacian step at strength 1
constexpr int kNormalPeriod = 4;     // sweeps between vertex normal updates

enum class Role : std::uint8_t { Sheet, Curve, Fixed, Fitted };

using Vec3 = std::array<double, 3>;

Vec3 cornerPosition(const Grid& grid, const int c[3]) {
  return {grid.originX + grid.spacingX * c[0], grid.originY + grid.spacingY * c[1],
          grid.layerZ[static_cast<std::size_t>(c[2])]};
}

// The point of the carrier nearest p in the least-squares sense of its affine span, with its
// barycentric weights clamped to >= kMargin.
Vec3 projectIntoCarrier(const Grid& grid, const Carrier& carrier, const Vec3& p) {
  const int n = carrier.count;
  Vec3 c[4] = {};
  for (int m = 0; m < n; ++m) c[m] = cornerPosition(grid, carrier.corners[m]);
  double e[3][3] = {};  // edge vectors c[m] - c[0]
  for (int m = 1; m < n; ++m)
    for (int a = 0; a < 3; ++a) e[m - 1][a] = c[m][a] - c[0][a];
  const Vec3 d = {p[0] - c[0][0], p[1] - c[0][1], p[2] - c[0][2]};
  double w[4] = {0, 0, 0, 0};
  const auto dot = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  if (n == 2) {
    w[1] = dot(d.data(), e[0]) / dot(e[0], e[0]);
  } else if (n == 3) {
    const double a = dot(e[0], e[0]), b = dot(e[0], e[1]), cc = dot(e[1], e[1]);
    const double r0 = dot(d.data(), e[0]), r1 = dot(d.data(), e[1]);
    const double det = a * cc - b * b;
    w[1] = (r0 * cc - r1 * b) / det;
    w[2] = (a * r1 - b * r0) / det;
  } else {
    // d = e0 w1 + e1 w2 + e2 w3, by Cramer's rule.
    const auto det3 = [](const double* x, const double* y, const double* z) {
      return x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) + x[2] * (y[0] * z[1] - y[1] * z[0]);
    };
    // Columns are e0, e1, e2: det of the matrix whose rows are the transposes is the same.
    const double det = det3(e[0], e[1], e[2]);
    w[1] = det3(d.data(), e[1], e[2]) / det;
    w[2] = det3(e[0], d.data(), e[2]) / det;
    w[3] = det3(e[0], e[1], d.data()) / det;
  }
  w[0] = 1;
  for (int m = 1; m < n; ++m) w[0] -= w[m];
  double sum = 0;
  for (int m = 0; m < n; ++m) sum += (w[m] = std::max(w[m], kMargin));
  Vec3 out{0, 0, 0};
  for (int m = 0; m < n; ++m)
    for (int a = 0; a < 3; ++a) out[a] += w[m] / sum * c[m][a];
  return out;
}

struct Adjacency {
  std::vector<Role> role;
  std::vector<std::uint32_t> start;  // size V + 1, into neighbours
  std::vector<std::uint32_t> neighbours;
  std::vector<Label> labels;  // 2 per vertex: the pair of its first triangle
  std::vector<std::uint32_t> triStart, triList;  // incident triangles per vertex
};

Adjacency buildAdjacency(const MultiLabelMesh& mesh, bool junctions, int threads) {
  const std::size_t vertexCount = mesh.vertexCount(), triangleCount = mesh.triangleCount();
  Adjacency adj;
  std::vector<std::uint32_t>& triStart = adj.triStart;
  std::vector<std::uint32_t>& triList = adj.triList;
  triStart.assign(vertexCount + 1, 0);
  triList.resize(3 * triangleCount);
  for (std::uint32_t v : mesh.triangles) ++triStart[v + 1];
  for (std::size_t v = 0; v < vertexCount; ++v) triStart[v + 1] += triStart[v];
  {
    std::vector<std::uint32_t> fill(triStart.begin(), triStart.end() - 1);
    for (std::size_t t = 0; t < triangleCount; ++t)
      for (int c = 0; c < 3; ++c) triList[fill[mesh.triangles[3 * t + c]]++] = static_cast<std::uint32_t>(t);
  }
  adj.role.assign(vertexCount, Role::Fixed);
  adj.labels.assign(2 * vertexCount, 0);
  std::vector<std::uint32_t> count(vertexCount, 0);

  // The neighbours of v (sheet or curve), written to out when not null; returns their count.
  const auto classify = [&](std::size_t v, std::vector<std::pair<std::uint32_t, std::uint32_t>>& scratch,
                            std::uint32_t* out) -> std::uint32_t {
    scratch.clear();
    bool onePair = true;
    std::uint32_t firstPair = 0;
    for (std::uint32_t i = triStart[v]; i < triStart[v + 1]; ++i) {
      const std::uint32_t t = triList[i];
      const std::uint32_t pair = mesh.labels[2 * t] | (static_cast<std::uint32_t>(mesh.labels[2 * t + 1]) << 16);
      if (i == triStart[v]) firstPair = pair;
      onePair &= pair == firstPair;
      for (int c = 0; c < 3; ++c)
        if (mesh.triangles[3 * t + c] != v) scratch.push_back({mesh.triangles[3 * t + c], pair});
    }
    std::sort(scratch.begin(), scratch.end());
    std::uint32_t all = 0, curve = 0;
    std::uint32_t curveNeighbours[2] = {0, 0};
    for (std::size_t i = 0; i < scratch.size();) {
      std::size_t e = i;
      while (e < scratch.size() && scratch[e].first == scratch[i].first) ++e;
      const bool junctionEdge = e - i != 2 || scratch[i].second != scratch[e - 1].second;
      if (out && onePair && all < count[v]) out[all] = scratch[i].first;
      ++all;
      if (junctionEdge) {
        if (curve < 2) curveNeighbours[curve] = scratch[i].first;
        ++curve;
      }
      i = e;
    }
    if (onePair && curve == 0) {
      adj.role[v] = Role::Sheet;
      return all;
    }
    if (junctions && curve == 2) {
      adj.role[v] = Role::Curve;
      if (out) out[0] = curveNeighbours[0], out[1] = curveNeighbours[1];
      return 2;
    }
    adj.role[v] = Role::Fixed;
    return 0;
  };

  parallelChunks(vertexCount, threads, [&](int, std::size_t begin, std::size_t end) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> scratch;
    for (std::size_t v = begin; v < end; ++v) {
      count[v] = classify(v, scratch, nullptr);
      if (triStart[v] < triStart[v + 1]) {
        const std::uint32_t t = triList[triStart[v]];
        adj.labels[2 * v] = mesh.labels[2 * t];
        adj.labels[2 * v + 1] = mesh.labels[2 * t + 1];
      }
    }
  });
  adj.start.assign(vertexCount + 1, 0);
  for (std::size_t v = 0; v < vertexCount; ++v) adj.start[v + 1] = adj.start[v] + count[v];
  adj.neighbours.resize(adj.start.back());
  parallelChunks(vertexCount, threads, [&](int, std::size_t begin, std::size_t end) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> scratch;
    for (std::size_t v = begin; v < end; ++v)
      if (count[v] > 0) classify(v, scratch, adj.neighbours.data() + adj.start[v]);
  });
  return adj;
}

// The area-weighted normal of v's triangles (all of one label pair for a sheet vertex).
Vec3 vertexNormal(const MultiLabelMesh& mesh, const Adjacency& adj, const std::vector<double>& p, std::size_t v) {
  Vec3 n{0, 0, 0};
  for (std::uint32_t i = adj.triStart[v]; i < adj.triStart[v + 1]; ++i) {
    const std::uint32_t* t = &mesh.triangles[3 * adj.triList[i]];
    const double* a = &p[3 * t[0]];
    const double* b = &p[3 * t[1]];
    const double* c = &p[3 * t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] += u[1] * w[2] - u[2] * w[1];
    n[1] += u[2] * w[0] - u[0] * w[2];
    n[2] += u[0] * w[1] - u[1] * w[0];
  }
  return n;
}

// Where the plane through target with normal n cuts the carrier edge (weights clamped to
// kMargin): the vertex follows the surface's normal motion and ignores tangential drift,
// which a nearest-point projection onto a slanted edge would turn into normal error. False
// when the edge runs nearly inside that plane.
bool slideAlongNormal(const Vec3& a, const Vec3& b, const Vec3& target, const Vec3& n, Vec3& out) {
  const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double en = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
  const double ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2], nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  if (en * en < 0.01 * ee * nn) return false;
  const double t = std::clamp(((target[0] - a[0]) * n[0] + (target[1] - a[1]) * n[1] + (target[2] - a[2]) * n[2]) / en,
                              kMargin, 1 - kMargin);
  for (int k = 0; k < 3; ++k) out[k] = a[k] + t * e[k];
  return true;
}

}  // namespace

SmoothingReport smoothMesh(MultiLabelMesh& mesh, const Grid& grid, const ContourSet* contours,
                           const SmoothingOptions& options, int threads, double sliceTolerance) {
  SmoothingReport report;
  const std::size_t vertexCount = mesh.vertexCount();
  if (!options.enabled || vertexCount == 0 || mesh.keys.size() != vertexCount) return report;
  Adjacency adj = buildAdjacency(mesh, options.junctions, threads);

  std::vector<double> cur(3 * vertexCount);
  for (std::size_t i = 0; i < cur.size(); ++i) cur[i] = mesh.positions[i];
  if (options.contourFit && contours) {
    const std::vector<double> t = fitContourCrossings(grid, *contours, mesh.keys, adj.labels, sliceTolerance, threads);
    for (std::size_t v = 0; v < vertexCount; ++v) {
      if (t[v] < 0) continue;
      const Carrier c = carrierOfKey(mesh.keys[v]);
      const double tc = std::clamp(t[v], kMargin, 1 - kMargin);
      const Vec3 a = cornerPosition(grid, c.corners[0]), b = cornerPosition(grid, c.corners[1]);
      for (int k = 0; k < 3; ++k) cur[3 * v + k] = a[k] + tc * (b[k] - a[k]);
      adj.role[v] = Role::Fitted;
    }
  }
  for (std::size_t v = 0; v < vertexCount; ++v) {
    if (adj.role[v] != Role::Fixed && adj.role[v] != Role::Fitted && carrierOfKey(mesh.keys[v]).count < 2)
      adj.role[v] = Role::Fixed;
    switch (adj.role[v]) {
      case Role::Sheet: ++report.sheet; break;
      case Role::Curve: ++report.curve; break;
      case Role::Fixed: ++report.fixed; break;
      case Role::Fitted: ++report.fitted; break;
    }
  }

  // Umbrella operator U(v) = mean of neighbours - v; zero where a vertex has none.
  std::vector<double> umbrella(3 * vertexCount, 0.0), next(cur), normals(3 * vertexCount, 0.0);
  // The carrier edge's ends of each sheet vertex (NaN otherwise), decoded once.
  std::vector<std::array<Vec3, 2>> edges(vertexCount);
  parallelChunks(vertexCount, threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const Carrier c = carrierOfKey(mesh.keys[v]);
      if (adj.role[v] == Role::Sheet && c.count == 2)
        edges[v] = {cornerPosition(grid, c.corners[0]), cornerPosition(grid, c.corners[1])};
      else
        edges[v][0][0] = std::numeric_limits<double>::quiet_NaN();
    }
  });
  const auto computeUmbrella = [&](const std::vector<double>& p, std::vector<double>& out) {
    parallelChunks(vertexCount, threads, [&](int, std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        const std::uint32_t s = adj.start[v], e = adj.start[v + 1];
        if (s == e) {
          out[3 * v] = out[3 * v + 1] = out[3 * v + 2] = 0;
          continue;
        }
        double sum[3] = {0, 0, 0};
        for (std::uint32_t i = s; i < e; ++i)
          for (int k = 0; k < 3; ++k) sum[k] += p[3 * adj.neighbours[i] + k];
        for (int k = 0; k < 3; ++k) out[3 * v + k] = sum[k] / (e - s) - p[3 * v + k];
      }
    });
  };
  // Each sweep moves a vertex by strength * (kTension * U - kBending * U^2), then into its
  // carrier. Bending alone is stable below 0.5 for uniform weights (eigenvalues of U^2 <= 4)
  // and would extrapolate a cap past the last contour by the chord slope of the rings below;
  // a little tension balances that (measured on spheres and tori, see smoothing_test.cpp).
  const double strength = std::clamp(options.strength, 0.0, 1.0);
  const double bending = kBending * strength, tension = kTension * strength;
  for (int it = 0; it < options.iterations; ++it) {
    computeUmbrella(cur, umbrella);
    // Normals turn slowly; refreshing them every few sweeps saves most of a sweep's time.
    if (it % kNormalPeriod == 0)
      parallelChunks(vertexCount, threads, [&](int, std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
          if (adj.role[v] == Role::Sheet) {
            const Vec3 n = vertexNormal(mesh, adj, cur, v);
            for (int k = 0; k < 3; ++k) normals[3 * v + k] = n[k];
          }
      });
    parallelChunks(vertexCount, threads, [&](int, std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        const Role role = adj.role[v];
        if (role == Role::Fixed || role == Role::Fitted) continue;
        const std::uint32_t s = adj.start[v], e = adj.start[v + 1];
        double sum[3] = {0, 0, 0};
        for (std::uint32_t i = s; i < e; ++i) {
          const double* u = &umbrella[3 * adj.neighbours[i]];
          sum[0] += u[0], sum[1] += u[1], sum[2] += u[2];
        }
        Vec3 target;
        const double inv = 1.0 / (e - s);
        for (int k = 0; k < 3; ++k) {
          const double u = umbrella[3 * v + k];
          target[k] = cur[3 * v + k] - bending * (sum[k] * inv - u) + tension * u;
        }
        Vec3 p;
        const bool onEdge = role == Role::Sheet && !std::isnan(edges[v][0][0]);
        if (!(onEdge && slideAlongNormal(edges[v][0], edges[v][1], target, {normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]}, p)))
          p = projectIntoCarrier(grid, carrierOfKey(mesh.keys[v]), target);
        for (int k = 0; k < 3; ++k) next[3 * v + k] = p[k];
      }
    });
    cur.swap(next);  // fixed and fitted vertices hold the same value in both buffers
  }
  for (std::size_t i = 0; i < cur.size(); ++i) mesh.positions[i] = static_cast<float>(cur[i]);
  return report;
}

}  // namespace scansurf
