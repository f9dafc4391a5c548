// scansurf: moves that keep triangles well shaped. Placing vertices on crossings and relaxing
// them makes slivers (assembled barycentres are well shaped; placed and smoothed, a few per
// cent of the triangles get an angle under 5 degrees).
// The guard shortens each vertex's move, on the segment from where it was, until no triangle's
// smallest angle is below min(limit, what it was before the move).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/mesh/incident_triangles.h"
#include "scansurf/surfaces.h"

namespace scansurf {

class AngleGuard {
 public:
  // The mesh's triangles (kept by reference: it must outlive the guard) and the smallest angle
  // to keep, degrees in (0, 60); limitDegrees <= 0 makes apply a no-op. `incident`: the mesh's
  // incidentTriangles where the caller has them (kept by reference), else built here.
  AngleGuard(const MultiLabelMesh& mesh, double limitDegrees, int threads, const IncidentTriangles* incident = nullptr);

  // before and after: every vertex's position, `stride` floats apart (x, y, z first; any further
  // floats are interpolated with them, e.g. a parameter along the vertex's edge). Pulls the
  // vertices of every triangle worse than allowed back toward `before`, a fifth of what is
  // left of their moves at a time (fully back after 20), until none is; each vertex ends on its segment
  // before -> after, so a convex region holding both ends (a lattice simplex) still holds it.
  // Requires that `before` itself is allowed (it is compared with itself). Deterministic for
  // any thread count. Returns how many vertices were pulled back. `watched`: the triangles that
  // can have moved (trianglesAround the vertices that may move); null: all of them.
  std::size_t apply(const float* before, float* after, int stride, const std::vector<std::uint32_t>* watched = nullptr);

  // The triangles of these vertices, ascending, each once.
  std::vector<std::uint32_t> trianglesAround(std::span<const std::uint32_t> vertices) const;

  bool enabled() const { return limitCosine_ < 1; }

 private:
  void appendTrianglesAround(std::span<const std::uint32_t> vertices, std::vector<std::uint8_t>& seen,
                             std::vector<std::uint32_t>& out) const;
  void findSharp(const float* before, const float* after, int stride, std::span<const std::uint32_t> candidates, bool all,
                 std::vector<std::vector<std::uint32_t>>& sharp) const;

  const MultiLabelMesh& mesh_;  // its triangles (its positions may be elsewhere meanwhile)
  const std::size_t vertexCount_;
  const float limitCosine_;  // cos(limit): a corner with a larger cosine is too sharp
  const int threads_;
  IncidentTriangles ownIncident_;
  const IncidentTriangles& incident_;
  std::vector<std::uint8_t> pulls_, inRound_, seen_;  // apply's scratch
};

}  // namespace scansurf
