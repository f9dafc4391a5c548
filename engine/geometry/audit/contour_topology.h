// scansurf: the topology a feature's contours imply for its surface, read off the slab rule's
// label volume (each contour plane's even-odd region held for its whole slab, consecutive
// planes stacked): how many closed surfaces bound it and their total genus.
//
// A digital set's topology depends on the adjacency chosen for it and its complement; the two
// consistent pairs (6 for the set with 26 for the complement, and 26 with 6; Kong & Rosenfeld,
// "Digital topology: introduction and survey", CVGIP 1989) differ only where voxels touch along
// an edge or at a corner. The surface's extraction may resolve such a touch either way, so the
// answer is a range spanning both pairs; where no voxel touches another that way, one figure.
#pragma once

#include "geometry/overlaps/overlap_analysis.h"

namespace scansurf {

struct TopologyRange {
  int minComponents = 0, maxComponents = 0;  // closed surfaces: solid parts plus enclosed cavities
  int minGenus = 0, maxGenus = 0;            // handles, summed over the surfaces
  bool empty() const { return maxComponents == 0; }
};

// The topology of the region's slab volume: its layers stacked in order, each layer's runs its
// pixels; a grid layer the list skips parts them (a long gap, capped on each side: own_slabs.h).
TopologyRange contourTopology(const FeatureRegion& region);

}  // namespace scansurf
