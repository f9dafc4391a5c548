// scansurf: contours too small for the grid, found before scan conversion (paper §3.4: a
// contour that covers no pixel centre leaves no trace in the classified volume).
#pragma once

#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"

namespace scansurf {

// One message per contour whose own even-odd region (the contour alone, holes ignored)
// contains no pixel centre of the grid, in feature, slice and contour order, naming the file,
// feature, slice z and contour index. Uses the half-open rule of insideRegion (polygon.h).
std::vector<std::string> findUncoveredContours(const ContourSet& contours, const Grid& grid);

// Whether the contour's region contains a pixel centre of the grid (in-plane only).
bool coversPixelCentre(const Contour& contour, const Grid& grid);

}  // namespace scansurf
