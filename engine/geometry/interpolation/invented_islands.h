// scansurf: the interpolated layers between two contour planes hold no part of a label that
// neither plane implies. Blending distance fields can leave, where three labels meet or a
// boundary turns, a few voxels of one label cut off from its region on both planes (a bubble
// of background inside a structure, a speck of a structure outside it): each becomes a
// separate closed surface that the contours never drew. Every connected part of a label
// (26-adjacency, the most generous, so that a structure shifting diagonally from layer to layer
// stays one part) that reaches neither plane takes the label that surrounds it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "scansurf/label_volume.h"

namespace scansurf {

// words: layers m = 0 .. factor-1 of one pair (m = 0 its lower plane A), nx * ny words each,
// label | clearance << 16, rewritten in place; planeB: the labels of its upper plane. A voxel
// given a new label gets `clearance`. Returns the number of voxels relabelled.
std::size_t removeInventedIslands(std::uint32_t* words, const Label* planeB, int nx, int ny, int factor, std::uint16_t clearance);

}  // namespace scansurf
