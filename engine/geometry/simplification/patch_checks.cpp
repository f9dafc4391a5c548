// scansurf: the checks a simplified patch passes before it replaces the original. Together they
// say the patch is the same surface piece (same border, Euler characteristic and components, a
// manifold with one orientation) whose contour-plane cross-sections gained no chord.
#include "geometry/simplification/patch_checks.h"

#include <algorithm>
#include <array>
#include <vector>

#include "geometry/mesh/mesh_topology.h"
#include "geometry/mesh/triangle_intersection.h"

namespace scansurf {
namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) { return std::uint64_t{a} << 32 | b; }
std::uint32_t from(std::uint64_t e) { return static_cast<std::uint32_t>(e >> 32); }
std::uint32_t to(std::uint64_t e) { return static_cast<std::uint32_t>(e); }

Point3 pointAt(std::span<const float> p, std::uint32_t v) {
  return {p[3 * std::size_t{v}], p[3 * std::size_t{v} + 1], p[3 * std::size_t{v} + 2]};
}

// Every triangle's three directed edges, sorted, and where each vertex's edges start: a counting
// sort by the first vertex (a patch's ids are local and few), then each vertex's few by the second.
struct DirectedEdges {
  std::vector<std::uint64_t> sorted;
  std::vector<std::uint32_t> start;  // vertexCount + 1 entries

  DirectedEdges(std::span<const std::uint32_t> tris, std::size_t vertexCount) : sorted(tris.size()), start(vertexCount + 1, 0) {
    for (std::uint32_t v : tris) ++start[v + 1];
    for (std::size_t v = 0; v < vertexCount; ++v) start[v + 1] += start[v];
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < tris.size(); t += 3)
      for (int c = 0; c < 3; ++c) sorted[fill[tris[t + c]]++] = edgeKey(tris[t + c], tris[t + (c + 1) % 3]);
    for (std::size_t v = 0; v < vertexCount; ++v) std::sort(sorted.begin() + start[v], sorted.begin() + start[v + 1]);
  }
  bool has(std::uint64_t e) const {
    const auto first = sorted.begin() + start[from(e)], last = sorted.begin() + start[from(e) + 1];
    return std::find(first, last, e) != last;
  }
};

// The directed edges whose reverse is not there: the border, sorted.
std::vector<std::uint64_t> borderOf(const DirectedEdges& edges) {
  std::vector<std::uint64_t> border;
  for (std::uint64_t e : edges.sorted)
    if (!edges.has(edgeKey(to(e), from(e)))) border.push_back(e);
  return border;
}

// Euler characteristic V - E + F and edge-connected components, of a patch whose directed
// edges (sorted) are unique.
std::array<long long, 2> topologyOf(std::span<const std::uint32_t> tris, const std::vector<std::uint64_t>& edges,
                                    std::size_t borderEdges, std::size_t vertexCount) {
  UnionFind sets(vertexCount);
  std::vector<char> used(vertexCount, 0);
  for (std::uint64_t e : edges) {
    used[from(e)] = used[to(e)] = 1;
    sets.unite(from(e), to(e));
  }
  long long vertices = 0, components = 0;
  for (std::uint32_t v = 0; v < vertexCount; ++v)
    if (used[v]) ++vertices, components += sets.find(v) == v;
  const auto undirected = static_cast<long long>((edges.size() + borderEdges) / 2);
  return {vertices - undirected + static_cast<long long>(tris.size() / 3), components};
}

// Per vertex, its corners in the triangles, sorted by vertex: {v, b, c} for each triangle (v, b, c).
std::vector<std::array<std::uint32_t, 3>> cornersOf(std::span<const std::uint32_t> tris) {
  std::vector<std::array<std::uint32_t, 3>> corners;
  corners.reserve(tris.size());
  for (std::size_t t = 0; t < tris.size(); t += 3)
    for (int c = 0; c < 3; ++c) corners.push_back({tris[t + c], tris[t + (c + 1) % 3], tris[t + (c + 2) % 3]});
  std::sort(corners.begin(), corners.end());
  return corners;
}

// No vertex is pinched after that was not before, and each vertex pinched before (where the
// patch meets it from two sides, on its border) keeps its triangles as they were: simplifyPatch
// leaves them, so its fans still join the same border edges.
bool noNewPinch(std::span<const std::uint32_t> before, std::span<const std::uint32_t> after, std::size_t vertexCount) {
  const std::vector<char> pinched = pinchedVertices(before, vertexCount), pinchedAfter = pinchedVertices(after, vertexCount);
  for (std::size_t v = 0; v < vertexCount; ++v)
    if (pinchedAfter[v] && !pinched[v]) return false;
  if (std::find(pinched.begin(), pinched.end(), 1) == pinched.end()) return true;
  const auto around = [&](std::span<const std::uint32_t> tris) {
    std::vector<std::array<std::uint32_t, 3>> kept;
    for (const auto& corner : cornersOf(tris))
      if (pinched[corner[0]]) kept.push_back(corner);
    return kept;
  };
  return around(before) == around(after);
}

// Both ends on one contour plane: a piece of its cross-section.
bool alongPlane(std::span<const int> plane, std::uint64_t e) { return plane[from(e)] >= 0 && plane[from(e)] == plane[to(e)]; }

// Every edge along a contour plane in `after` is one of `before`'s (either direction).
bool noNewPlaneEdge(std::span<const int> plane, const DirectedEdges& before, const DirectedEdges& after) {
  for (std::uint64_t e : after.sorted)
    if (alongPlane(plane, e) && !before.has(e) && !before.has(edgeKey(to(e), from(e)))) return false;
  return true;
}

Point3 normalOf(std::span<const float> p, const std::uint32_t* t) {
  const Point3 a = pointAt(p, t[0]);
  return cross(pointAt(p, t[1]) - a, pointAt(p, t[2]) - a);
}

// A triangle's corners from its smallest index on (the same triangle, however listed).
std::array<std::uint32_t, 3> canonical(const std::uint32_t* t) {
  const int k = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
  return {t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
}

// Every new triangle of `after` faces the same side as `before`'s area-weighted normal at each
// of its corners (the triangles kept as they were may face as they did).
bool noneTurned(std::span<const float> p, std::span<const std::uint32_t> before, std::span<const std::uint32_t> after,
                const std::vector<char>& fresh) {
  std::vector<Point3> normal(p.size() / 3, Point3{0, 0, 0});
  for (std::size_t t = 0; t < before.size(); t += 3) {
    const Point3 n = normalOf(p, &before[t]);
    for (int c = 0; c < 3; ++c) normal[before[t + c]] = normal[before[t + c]] + n;
  }
  for (std::size_t t = 0; t < after.size(); t += 3) {
    if (!fresh[t / 3]) continue;
    const Point3 n = normalOf(p, &after[t]);
    for (int c = 0; c < 3; ++c)
      if (dot(n, normal[after[t + c]]) <= 0) return false;
  }
  return true;
}

bool anyDegenerate(std::span<const float> p, std::span<const std::uint32_t> tris) {
  for (std::size_t t = 0; t < tris.size(); t += 3)
    if (isDegenerate({pointAt(p, tris[t]), pointAt(p, tris[t + 1]), pointAt(p, tris[t + 2])})) return true;
  return false;
}

}  // namespace

std::vector<char> pinchedVertices(std::span<const std::uint32_t> triangles, std::size_t vertexCount) {
  // Each vertex's link edges, bucketed by vertex (a counting sort: the ids are local and few).
  std::vector<std::uint32_t> start(vertexCount + 1, 0);
  for (std::uint32_t v : triangles) ++start[v + 1];
  for (std::size_t v = 0; v < vertexCount; ++v) start[v + 1] += start[v];
  std::vector<std::array<std::uint32_t, 2>> link(triangles.size());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < triangles.size(); t += 3)
    for (int c = 0; c < 3; ++c) link[fill[triangles[t + c]]++] = {triangles[t + (c + 1) % 3], triangles[t + (c + 2) % 3]};
  std::vector<char> pinched(vertexCount, 0);
  std::vector<std::uint32_t> scratch;
  for (std::size_t v = 0; v < vertexCount; ++v)
    if (start[v + 1] > start[v]) pinched[v] = !singleFan(std::span(link).subspan(start[v], start[v + 1] - start[v]), scratch);
  return pinched;
}

std::vector<char> newTriangles(std::span<const std::uint32_t> before, std::span<const std::uint32_t> after) {
  std::vector<std::array<std::uint32_t, 3>> old;
  for (std::size_t t = 0; t < before.size(); t += 3) old.push_back(canonical(&before[t]));
  std::sort(old.begin(), old.end());
  std::vector<char> fresh(after.size() / 3);
  for (std::size_t t = 0; t < after.size(); t += 3)
    fresh[t / 3] = !std::binary_search(old.begin(), old.end(), canonical(&after[t]));
  return fresh;
}

PatchVerdict checkPatch(std::span<const float> positions, std::span<const int> plane, std::span<const std::uint32_t> before,
                        std::span<const std::uint32_t> after, std::vector<char>* fresh) {
  if (anyDegenerate(positions, after)) return PatchVerdict::Degenerate;
  const std::size_t vertices = plane.size();
  const DirectedEdges edgesBefore(before, vertices), edgesAfter(after, vertices);
  if (std::adjacent_find(edgesAfter.sorted.begin(), edgesAfter.sorted.end()) != edgesAfter.sorted.end())
    return PatchVerdict::NotOriented;
  const std::vector<std::uint64_t> borderBefore = borderOf(edgesBefore), borderAfter = borderOf(edgesAfter);
  if (borderBefore != borderAfter) return PatchVerdict::Border;
  if (topologyOf(before, edgesBefore.sorted, borderBefore.size(), vertices) !=
      topologyOf(after, edgesAfter.sorted, borderAfter.size(), vertices))
    return PatchVerdict::Topology;
  if (!noNewPinch(before, after, vertices)) return PatchVerdict::Pinched;
  if (!noNewPlaneEdge(plane, edgesBefore, edgesAfter)) return PatchVerdict::PlaneEdge;
  std::vector<char> isNew = newTriangles(before, after);
  if (!noneTurned(positions, before, after, isNew)) return PatchVerdict::Turned;
  if (fresh) *fresh = std::move(isNew);
  return PatchVerdict::Kept;
}

}  // namespace scansurf
