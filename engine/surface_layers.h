// scansurf: the bookkeeping of a build in several surface layers (features that partly overlap
// by design, OverlapReport::layers): each layer's contours, its part of the grid, and its
// surfaces appended to the run's.
#pragma once

#include <vector>

#include "geometry/overlaps/overlap_analysis.h"
#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// The contour set with only `layer`'s features drawn: the others keep their index (and so
// every label) but lose their slices.
ContourSet layerContours(const ContourSet& contours, const OverlapReport& report, int layer);

// Appends a layer's surfaces of its own features to `into` (vertices not shared across layers).
// Layer 0 holds most of the surface and is moved in, not copied: the later layers (a few
// planning volumes or marks) are then appended to it.
void appendLayer(Surfaces& into, Surfaces&& layer, const OverlapReport& report, int index);

// The part of the grid a layer's features occupy, with one background voxel around them, on
// the same lattice: later layers (usually a few planning volumes or marks) then cost what their
// extent costs, not the whole volume. Layer 0 keeps the whole grid (BuildResult::volume).
Grid layerGrid(const Grid& grid, const std::vector<FeatureRegion>& regions, const OverlapReport& report, int layer);

}  // namespace scansurf
