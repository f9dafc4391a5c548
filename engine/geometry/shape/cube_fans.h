// scansurf: fewer triangles where a separating surface crosses voxel cubes as fans.
// The Freudenthal cut gives a flat wall about eight triangles per cube, around a vertex on the
// cube's body diagonal; marching cubes gives two. Where a cube's (or a box of cubes') surface is
// one label pair's disk, the vertices inside go and the disk's rim is triangulated again: a
// vertex and two triangles fewer for each, nothing else moved.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "scansurf/grid.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// The re-triangulated regions (cubes and blocks): each one's rim and new triangles, and the axis
// along which its new disk is seen one-to-one (what keeps it from folding onto itself when its
// rim moves).
struct CubeDisks {
  std::vector<std::uint32_t> rimStart{0};       // per disk, where its rim starts in `rims` (+ the end)
  std::vector<std::uint32_t> rims;              // rim vertices in the triangles' orientation
  std::vector<std::uint32_t> triangleStart{0};  // per disk, where its (rim size - 2) triangles start in `triangles`
  std::vector<std::uint32_t> triangles;         // mesh triangle indices
  std::vector<std::uint8_t> view;               // per disk: the axis it is seen along, + 3 from below
  std::size_t removedVertices = 0;              // the mesh lost these and twice as many triangles

  std::size_t count() const { return view.size(); }
};

// Every box of 2 x 2 x 2 cubes, then 2 x 2 x 1, then 1 x 1 x 2 (at even voxel indices in x and
// y, both parities in z where two thick), and then every cube not in such a box, whose triangles
// carry one label pair and form one disk with its rim on the box's faces and every other vertex
// strictly inside the box gets the rim's triangulation with the largest smallest angle that adds
// no edge inside one face of the box nor across its middle layer, if that triangulation projects
// one-to-one along an axis, faces the way the old disk did, passes within 0.05 of the box's
// finest lattice spacing (pixel or layer gap) of every removed vertex, is no sharper than both
// 15 degrees and the sharpest triangle it replaces and, two layers thick, cuts its middle layer
// along one chord within that distance of the old cut and further from the box's inner voxel
// centre. The new triangles lie in the open box, so they meet no other box's; the rim and the
// shared interfaces stay (cube_fans.cpp). Needs mesh.keys and triangles in cell order
// (assemblyMesh's; snapping and the quad diagonals keep it); a mesh out of that order is left as
// it is. Vertices stay in key order; onSheet follows them. Deterministic for any thread count
// (0 = all).
CubeDisks retriangulateCubeFans(MultiLabelMesh& mesh, const Grid& grid, std::vector<bool>& onSheet, int threads = 0);

// Whether every disk's new triangles and rim still project one-to-one along its axis (exact).
bool disksEmbedded(const CubeDisks& disks, const MultiLabelMesh& mesh, int threads = 0);

// After vertices moved from `before` (xyz per vertex): every disk that no longer projects
// one-to-one gets its rim's vertices back where they were, until every disk does (all back is
// where they all did). Returns the vertices put back. Deterministic for any thread count.
std::size_t keepDisksEmbedded(const CubeDisks& disks, MultiLabelMesh& mesh, const std::vector<float>& before, int threads = 0);

}  // namespace scansurf
