// scansurf: whether a simplified surface patch may replace the original (simplify_mesh.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace scansurf {

// What a patch's simplification must keep, or the first thing it lost.
enum class PatchVerdict {
  Kept,
  Degenerate,   // a triangle with collinear corners (exact test)
  NotOriented,  // a directed edge used twice: not a manifold with one orientation
  Border,       // the edges used one way only changed
  Topology,     // Euler characteristic or edge-connected components changed
  Pinched,      // a vertex whose triangles form more than one fan, or one that did whose triangles changed
  PlaneEdge,    // an edge along a contour plane that the original did not have
  Turned,       // a triangle facing against the original surface at one of its corners
};

// Compares `after` with `before` (3 indices per triangle into positions, xyz per vertex);
// plane[v] is the contour plane vertex v lies on, or -1. When kept, `fresh` (if given) gets
// newTriangles(before, after), which the last check needs anyway.
PatchVerdict checkPatch(std::span<const float> positions, std::span<const int> plane, std::span<const std::uint32_t> before,
                        std::span<const std::uint32_t> after, std::vector<char>* fresh = nullptr);

// Per vertex, whether its triangles form more than one fan (a patch's border vertex may).
std::vector<char> pinchedVertices(std::span<const std::uint32_t> triangles, std::size_t vertexCount);

// Per triangle of `after`, whether it is new: not one of `before`'s, however its corners are listed.
std::vector<char> newTriangles(std::span<const std::uint32_t> before, std::span<const std::uint32_t> after);

}  // namespace scansurf
