// scansurf benchmark: how far retriangulating each cube's surface patch could cut the default
// triangle count (issue 28; the design is in docs/benchmarks.md, "Why the 2x speed target...").
//
//   scansurf_bench_cell_census INPUT.json NX NY
//
// Builds INPUT.json as one partition on an NX x NY grid with the default smoothing, then visits
// every voxel cube the surface passes through. A cube qualifies when its triangles carry one
// label pair and form a disk around one inner vertex (on the body diagonal; every other vertex
// of a two-label cube lies on the cube's boundary). Its boundary polygon is then triangulated
// with the most-even smallest angle, using no new edge between two vertices on one cube face,
// so the new triangles lie strictly inside the cube and cannot cross another cube's. Prints the
// counts, the triangles saved (two per retriangulated cube), the angle figures before and after
// and how far the removed vertices lie from the new triangles. Measures; changes no output.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

#include "geometry/remesh.h"
#include "geometry/vec3.h"
#include "io/contours_json.h"
#include "scansurf/engine.h"

using namespace scansurf;

namespace {

constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
std::array<std::int64_t, 3> unpack(std::uint64_t key) {
  return {static_cast<std::int64_t>(key & kMask), static_cast<std::int64_t>((key >> 21) & kMask),
          static_cast<std::int64_t>(key >> 42)};
}

Vec3 at(const MultiLabelMesh& m, std::uint32_t v) { return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}; }

// Cube of a triangle: its keys' centroid lies strictly inside one tetrahedron of one cube.
std::uint64_t cubeOf(const MultiLabelMesh& m, std::size_t t) {
  std::array<std::int64_t, 3> sum{};
  for (int c = 0; c < 3; ++c) {
    const auto k = unpack(m.keys[m.triangles[3 * t + c]]);
    for (int a = 0; a < 3; ++a) sum[a] += k[a];
  }
  return static_cast<std::uint64_t>(sum[0] / 36) | static_cast<std::uint64_t>(sum[1] / 36) << 21 |
         static_cast<std::uint64_t>(sum[2] / 36) << 42;
}

// Bit f of the result: the vertex lies on face f (x low, x high, y low, ...) of the cube.
int facesOf(std::uint64_t key, std::uint64_t cube) {
  const auto k = unpack(key), c = unpack(cube);
  int mask = 0;
  for (int a = 0; a < 3; ++a) mask |= (k[a] == 12 * c[a] ? 1 : 0) << (2 * a) | (k[a] == 12 * c[a] + 12 ? 2 : 0) << (2 * a);
  return mask;
}

double smallestAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, v = r - p;
    return std::atan2(length(cross(u, v)), dot(u, v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)}) * 180.0 / M_PI;
}

double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(b - a, c - a);
  const double area2 = length(n);
  if (area2 > 0) {  // inside the prism over the triangle: the plane distance
    const Vec3 u = n / area2;
    const Vec3 q = p - u * dot(p - a, u);
    if (dot(cross(b - a, q - a), n) >= 0 && dot(cross(c - b, q - b), n) >= 0 && dot(cross(a - c, q - c), n) >= 0)
      return std::abs(dot(p - a, u));
  }
  const auto segment = [&](const Vec3& s, const Vec3& e) {
    const Vec3 d = e - s;
    const double t = std::clamp(dot(p - s, d) / std::max(dot(d, d), 1e-300), 0.0, 1.0);
    return length(p - (s + d * t));
  };
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

// The boundary cycle of a disk of triangles, in the triangles' orientation; empty if the
// triangles are not one disk around one inner vertex.
std::vector<std::uint32_t> boundaryCycle(const MultiLabelMesh& m, const std::vector<std::size_t>& tris) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t t : tris)
    for (int c = 0; c < 3; ++c) ++directed[{m.triangles[3 * t + c], m.triangles[3 * t + (c + 1) % 3]}];
  std::map<std::uint32_t, std::uint32_t> next;
  for (const auto& [e, n] : directed)
    if (!directed.count({e.second, e.first})) {
      if (next.count(e.first)) return {};
      next[e.first] = e.second;
    }
  if (next.size() != tris.size() || next.empty()) return {};  // a disk around one inner vertex: F = n
  std::vector<std::uint32_t> cycle{next.begin()->first};
  while (cycle.size() <= next.size()) {
    const auto it = next.find(cycle.back());
    if (it == next.end()) return {};
    if (it->second == cycle.front()) break;
    cycle.push_back(it->second);
  }
  return cycle.size() == next.size() ? cycle : std::vector<std::uint32_t>{};
}

struct Retriangulation {
  bool feasible = false;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// Max-min-angle triangulation of the polygon with no new edge inside one cube face (dynamic
// programming over sub-polygons, O(n^3)).
Retriangulation triangulate(const MultiLabelMesh& m, const std::vector<std::uint32_t>& poly, std::uint64_t cube) {
  const std::size_t n = poly.size();
  std::vector<int> faces(n);
  for (std::size_t i = 0; i < n; ++i) faces[i] = facesOf(m.keys[poly[i]], cube);
  const auto allowed = [&](std::size_t i, std::size_t j) {
    return (j - i) % n == 1 || (i + n - j) % n == 1 || !(faces[i] & faces[j]);
  };
  std::vector<double> best(n * n, -1);
  std::vector<std::size_t> split(n * n, 0);
  for (std::size_t i = 0; i + 1 < n; ++i) best[i * n + i + 1] = 180;
  for (std::size_t len = 2; len < n; ++len)
    for (std::size_t i = 0; i + len < n; ++i) {
      const std::size_t j = i + len;
      if (!allowed(i, j)) continue;
      for (std::size_t k = i + 1; k < j; ++k) {
        const double q =
            std::min({best[i * n + k], best[k * n + j], smallestAngle(at(m, poly[i]), at(m, poly[k]), at(m, poly[j]))});
        if (best[i * n + k] >= 0 && best[k * n + j] >= 0 && q > best[i * n + j]) best[i * n + j] = q, split[i * n + j] = k;
      }
    }
  Retriangulation r;
  if (best[n - 1] < 0) return r;
  r.feasible = true;
  std::vector<std::pair<std::size_t, std::size_t>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const std::size_t k = split[i * n + j];
    r.triangles.push_back({poly[i], poly[k], poly[j]});
    stack.push_back({i, k}), stack.push_back({k, j});
  }
  return r;
}

struct Census {
  std::size_t cubes = 0, qualifying = 0, feasible = 0;
  std::vector<std::uint32_t> triangles;  // the mesh after retriangulating every feasible cube
  double removedMean = 0, removedMax = 0;
};

void visitCube(const MultiLabelMesh& m, std::uint64_t cube, const std::vector<std::size_t>& tris, Census& out) {
  const auto keep = [&] {
    for (std::size_t t : tris) out.triangles.insert(out.triangles.end(), &m.triangles[3 * t], &m.triangles[3 * t] + 3);
  };
  ++out.cubes;
  for (std::size_t t : tris)
    if (m.labels[2 * t] != m.labels[2 * tris[0]] || m.labels[2 * t + 1] != m.labels[2 * tris[0] + 1]) return keep();
  const std::vector<std::uint32_t> poly = boundaryCycle(m, tris);
  if (poly.empty() || poly.size() > 24) return keep();
  std::uint32_t inner = ~0u;
  for (std::size_t t : tris)
    for (int c = 0; c < 3; ++c)
      if (const std::uint32_t v = m.triangles[3 * t + c]; facesOf(m.keys[v], cube) == 0) {
        if (inner != ~0u && inner != v) return keep();
        inner = v;
      }
  if (inner == ~0u) return keep();
  ++out.qualifying;
  const Retriangulation r = triangulate(m, poly, cube);
  if (!r.feasible) return keep();
  ++out.feasible;
  double d = 1e300;
  for (const auto& t : r.triangles) {
    out.triangles.insert(out.triangles.end(), t.begin(), t.end());
    d = std::min(d, pointTriangleDistance(at(m, inner), at(m, t[0]), at(m, t[1]), at(m, t[2])));
  }
  out.removedMean += d, out.removedMax = std::max(out.removedMax, d);
}

Census census(const MultiLabelMesh& m) {
  std::vector<std::pair<std::uint64_t, std::size_t>> byCube(m.triangleCount());
  for (std::size_t t = 0; t < byCube.size(); ++t) byCube[t] = {cubeOf(m, t), t};
  std::sort(byCube.begin(), byCube.end());
  Census out;
  std::vector<std::size_t> tris;
  for (std::size_t i = 0; i < byCube.size();) {
    tris.clear();
    std::size_t j = i;
    for (; j < byCube.size() && byCube[j].first == byCube[i].first; ++j) tris.push_back(byCube[j].second);
    visitCube(m, byCube[i].first, tris, out);
    i = j;
  }
  if (out.feasible) out.removedMean /= static_cast<double>(out.feasible);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: scansurf_bench_cell_census INPUT.json NX NY\n");
    return 2;
  }
  auto contours = readContoursJson(argv[1]);
  auto engine = Engine::create({});
  if (!contours || !engine) {
    std::fprintf(stderr, "%s\n", (!contours ? contours.error() : engine.error()).message.c_str());
    return 1;
  }
  BuildOptions options;
  options.grid.nx = std::atoi(argv[2]), options.grid.ny = std::atoi(argv[3]);
  options.overlaps = OverlapMode::Partition;  // one label volume, one mesh
  options.smoothing.enabled = true;
  auto built = engine->build(*contours, options);
  if (!built) {
    std::fprintf(stderr, "%s\n", built.error().message.c_str());
    return 1;
  }
  const MultiLabelMesh& m = built->surfaces.mesh;
  const double voxel = std::min(built->volume.grid.spacingX, built->volume.grid.spacingY);
  const Census c = census(m);
  const AngleFigures before = computeAngleFigures(m.positions, m.triangles);
  const AngleFigures after = computeAngleFigures(m.positions, c.triangles);
  std::printf(
      "%s at %d x %d: %zu triangles in %zu cubes; %zu cubes are two-label disks around an inner vertex, %zu of them "
      "retriangulable inside the cube\n",
      argv[1], options.grid.nx, options.grid.ny, m.triangleCount(), c.cubes, c.qualifying, c.feasible);
  std::printf(
      "triangles %zu -> %zu (%.3fx); smallest / 5th percentile / mean angle %.1f / %.1f / %.1f -> %.1f / %.1f / %.1f deg\n",
      m.triangleCount(), c.triangles.size() / 3,
      static_cast<double>(c.triangles.size() / 3) / static_cast<double>(m.triangleCount()), before.min, before.p5, before.mean,
      after.min, after.p5, after.mean);
  std::printf("removed vertices from the new triangles: mean %.4f, max %.4f voxel\n", c.removedMean / voxel,
              c.removedMax / voxel);
  return 0;
}
