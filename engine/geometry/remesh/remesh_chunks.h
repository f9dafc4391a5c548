// scansurf: remeshing in parallel, the same output for any thread count. The network is cut
// into chunks along z at fixed triangle-count quantiles (from the mesh alone, never from the
// thread count). Phase 0 remeshes each chunk on its own, with everything on its cut planes
// pinned; phase 1 remeshes a band around each cut, everything outside the band pinned. The
// units of one phase run concurrently and are merged back in their order.
//
// Why units of one phase cannot interfere: a unit's new triangles must lie strictly between
// its region's lo and hi in z (checked with the other checks), it edits only triangles with a
// free vertex, and those lie strictly inside the region as well (a triangle reaching a bound
// has all its vertices pinned). The regions of one phase are disjoint, so every triangle that
// a unit's crossing checks could meet is in its submesh and no other unit changes it; every
// vertex an edit touches lies inside the region, so its whole fan is in the submesh and the
// topology checks see what the whole network would.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/remesh/remesh_network.h"

namespace scansurf::remesh {

// One piece of work: new triangles strictly between lo and hi in z; vertices strictly between
// freeLo and freeHi may move or go, the others are pinned.
struct WorkUnit {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double lo = -kInf, hi = kInf, freeLo = -kInf, freeHi = kInf;
  std::size_t triangles = 0;  // input triangles centred in [freeLo, freeHi): the work to expect
  bool whole() const { return lo == -kInf && hi == kInf && freeLo == -kInf && freeHi == kInf; }
};

// The units of both phases. One whole unit in phase 0 and none in phase 1 when the mesh has
// fewer than two chunks' worth of triangles or is too flat to cut.
struct ChunkPlan {
  std::vector<WorkUnit> phases[2];
};
ChunkPlan planChunks(const MultiLabelMesh& mesh, double edgeLength, std::size_t trianglesPerChunk);

// A unit's part of the network, its vertices renumbered in the whole mesh's order.
struct SubMesh {
  MultiLabelMesh mesh;
  std::vector<std::uint32_t> globalVertex;          // per local vertex
  std::vector<char> pinned;                         // per local vertex
  std::vector<char> rim;                            // per local vertex: some of its triangles are not in the submesh
  std::vector<char> settled;                        // per local vertex: remeshed by an earlier phase
  std::vector<std::uint32_t> editable;              // whole-mesh triangles with a free vertex
  std::vector<std::array<std::uint32_t, 4>> fixed;  // the others: sorted local corners and pair, sorted
};
// `valence`: the whole mesh's triangles per vertex; `settled`: per vertex, whether an earlier
// phase remeshed it (empty: none did).
SubMesh extractUnit(const MultiLabelMesh& mesh, const std::vector<std::uint32_t>& valence, const std::vector<char>& settled,
                    const WorkUnit& unit);
std::vector<std::uint32_t> vertexValence(const MultiLabelMesh& mesh);

// What a unit's remesher left: every local vertex's position (new ones after the submesh's)
// and the triangles it made or kept that are not among the submesh's fixed ones.
struct UnitResult {
  std::vector<Vec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // local ids
  std::vector<std::uint32_t> pairs;
};

// Replaces each unit's editable triangles by its result, in unit order; new vertices are
// appended in that order. Vertices no triangle uses any more stay until compactVertices.
// Marks in `settled` (per vertex, grown to the new count) every vertex a unit was free to
// move and every new one.
void mergeUnits(MultiLabelMesh& mesh, const std::vector<SubMesh>& subs, const std::vector<UnitResult>& results,
                std::vector<char>& settled);
// Drops the vertices no triangle uses, keeping the others' order.
void compactVertices(MultiLabelMesh& mesh);

}  // namespace scansurf::remesh
