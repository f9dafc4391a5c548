// scansurf: smoothing that keeps each structure's volume. Relaxation (smoothing.cpp) shrinks
// small convex structures and swells thin ones (a 3 mm scar on two slices at 1 mm pixels lost
// 17 % of its slab volume, discs on one or two slices gained 4 %); this restores, after it,
// every feature's enclosing volume to a target (the slab rule its contours define) by moving
// its free vertices along their volume gradient, each still strictly inside its own
// lattice simplex, so every guarantee of the smoothing stands (no crossing, same topology,
// contour planes and junction curves where they were).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "scansurf/grid.h"
#include "scansurf/nesting.h"
#include "scansurf/surfaces.h"

namespace scansurf {

struct VolumeRestorationReport {
  int features = 0;        // features restored (a target, movable vertices)
  double worstBefore = 0;  // largest |volume - target| / target before, and after
  double worstAfter = 0;
  std::size_t movedVertices = 0;
  std::size_t heldBack = 0;  // vertex moves undone to keep a cube's disk unfolded (cube_fans.h)
};

struct CubeDisks;

// mesh: the smoothed multi-label mesh (keys intact) on `grid`; targets[f]: feature f's enclosing
// volume to restore (input units cubed; <= 0 or missing: leave it); onSheet[v]: vertex v is on
// one label pair's sheet (SmoothingReport::onSheet); contourLayers[k]: layer k is a contour
// plane, whose in-plane vertices stay on the contours. Only sheet vertices off the contour
// planes whose triangles all bound the same features from one side move: one feature's surface,
// and where it reaches out of a container, the container's too (an interface between siblings,
// a junction or a contour stays). A feature's region is its label's and its descendants'
// (Nesting::parent), among the labels in the mesh. Moves that would leave a triangle sharper
// than minAngle degrees (and than it was) are shortened (geometry/smoothing/angle_guard.h; 0: off); moves
// that would fold one of `disks` (retriangulateCubeFans's; null: none) are undone. The vertices
// whose keys are in `held` (sorted; SmoothingReport::betweenPlanes) move only in a second pass,
// for the features that the others could not bring to their targets: the volume that the slab
// rule and the blended shape disagree on goes to the caps and the junctions, where the contours
// say least, rather than into ripples between every pair of planes.
VolumeRestorationReport restoreVolumes(MultiLabelMesh& mesh, const Grid& grid, const Nesting& nesting,
                                       std::span<const double> targets, const std::vector<bool>& onSheet,
                                       const std::vector<bool>& contourLayers, double minAngle, int threads,
                                       const CubeDisks* disks = nullptr, std::span<const std::uint64_t> held = {});

}  // namespace scansurf
