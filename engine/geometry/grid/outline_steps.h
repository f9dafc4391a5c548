// scansurf: how far each structure's outline moves between consecutive contour planes, which
// decides how many layers interpolation puts between them (interpolationFactors): a step of
// more than about one pixel between surfaced layers shows as a terrace.
#pragma once

#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"

namespace scansurf {

// steps[k]: the largest move, in pixels of the smaller spacing, of any feature's outline between
// grid layers k and k + 1 where it is on both: how far an edge of its bounding box moves, or its
// equivalent radius changes. A feature that begins or ends in a gap counts nothing there (its cap
// closes it).
std::vector<double> outlineSteps(const ContourSet& contours, const Grid& grid);

}  // namespace scansurf
