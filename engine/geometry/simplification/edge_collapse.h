// scansurf: quadric-error half-edge collapses with a local veto (Garland & Heckbert, "Surface
// simplification using quadric error metrics", SIGGRAPH 1997), one surface patch at a time.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace scansurf {

struct CollapseLimits {
  double maxDistance = 0;  // a vertex may move at most this far from any plane of the triangles it merged, input units
  double maxEdge = 0;      // no new edge longer than this, input units
  // New triangles keep a smallest angle of at least the lesser of this and the smallest angle of
  // the triangles they replace, degrees: collapses never make the shape worse below it.
  double minAngle = 0;
};

// Collapses edges of the patch (3 indices per triangle into xyz positions) in order of quadric
// error, each moving a vertex onto a neighbour; vertices with locked[v] never move, and those
// with locked[v] == kFrozen keep their triangles too (no flip at them). A collapse is
// made only if it keeps the patch a manifold (link condition), turns no triangle by more than
// 60 degrees, to a degenerate one or against the patch's normal at one of its corners, keeps the
// limits (an edge no longer than maxDistance counts as within it), and adds no edge between two
// vertices on one contour plane (plane[v], -1 for none) that were not joined. Then flips the
// patch's inner edges where that blunts the two triangles' sharpest corner, within the same
// rules (the two triangles' tetrahedron no thicker than maxDistance), and collapses again.
// Returns the triangles left, in the same indices; the same output for the same input.
inline constexpr char kFrozen = 2;
std::vector<std::uint32_t> collapseEdges(std::span<const float> positions, std::span<const std::uint32_t> triangles,
                                         std::span<const char> locked, std::span<const int> plane, const CollapseLimits& limits);

}  // namespace scansurf
