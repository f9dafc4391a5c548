// scansurf: between two contour planes, every label keeps the topology the slab rule gives it
// (each plane's region held half way to the other): no island, handle or cavity that neither
// plane implies, and every branching they do imply.
//
// Blending distance fields can invent all three where outlines turn or three labels meet. The
// interpolated labels are reached from the slab rule's by flipping one voxel at a time, and
// only voxels that are simple for both labels of the flip (Bertrand & Malandain, "A new
// characterization of three-dimensional simple points", Pattern Recognition Letters 15, 1994:
// removing or adding a simple point changes no component, cavity or tunnel of the set or of
// its complement), with the adjacency the surfaces are extracted with: the edges of the
// cells' Freudenthal tetrahedra, 14 neighbours a voxel; a voxel whose flip would change
// the topology keeps the slab rule's label. This is the homotopic deformation of topology-
// preserving segmentation (Han, Xu & Prince, IEEE TPAMI 25, 2003), from the slab rule toward
// the interpolation.
#pragma once

#include <cstddef>
#include <cstdint>

#include "scansurf/label_volume.h"

namespace scansurf {

// words: layers m = 0 .. factor-1 of one pair (m = 0 its lower plane), nx * ny words each,
// label | clearance << 16; those between the planes are rewritten in place. planeA, planeB:
// the labels of its two planes. A voxel left at the slab rule's label gets `clearance`.
// Returns the number of such voxels.
std::size_t keepSlabTopology(std::uint32_t* words, const Label* planeA, const Label* planeB, int nx, int ny, int factor,
                             std::uint16_t clearance);

}  // namespace scansurf
