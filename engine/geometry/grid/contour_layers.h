// scansurf: which layers of a grid hold contours (volume restoration and simplification keep
// those planes' cross-sections).
#pragma once

#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"

namespace scansurf {

// Per layer of the grid: whether a slice of `contours` lies on it (Grid::layerOfPlane); all
// false when contours is null.
std::vector<bool> contourLayers(const Grid& grid, const ContourSet* contours);

}  // namespace scansurf
