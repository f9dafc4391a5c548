// scansurf: each feature's own slabs. The grid's layers are the planes of every feature, so a
// feature drawn on planes 0, 4, 8 among features drawn on 2 and 6 meets layers it has no
// contour on; left as background there it was cut into one piece per plane, and its surface
// and volume depended on which other features were selected. The slab rule of its own planes
// (each plane's region reaches half way to the feature's next plane) says what it holds there:
// the nearer own plane's contours (ties: the lower plane), except across a gap far longer than
// the feature's usual spacing, which the slab rule would bridge with a vertical-walled lid.
#pragma once

#include <optional>
#include <vector>

#include "geometry/contours/plane_gaps.h"
#include "scansurf/contours.h"
#include "scansurf/grid.h"

namespace scansurf {

// A feature's long gap (plane_gaps.h) on the grid: the slab rule does not bridge it, each side
// is capped on its own on the layers between them.
struct LongGap : PlaneGap {
  bool capped = false;  // the grid has a layer between the planes, left empty
};

// Every feature's long gaps (gapFactor 0: none), in feature order, then by z.
std::vector<LongGap> longGaps(const ContourSet& contours, const Grid& grid, double gapFactor);

// The contour set with, for each feature, a slice on every layer of `grid` strictly between two
// of its consecutive planes, holding the nearer plane's contours, except across its long gaps
// (longGaps); nullopt when no feature needs one (the set is used as it is).
std::optional<ContourSet> withOwnSlabs(const ContourSet& contours, const Grid& grid, double gapFactor);

}  // namespace scansurf
