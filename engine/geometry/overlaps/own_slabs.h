// scansurf: each feature's own slabs. The grid's layers are the planes of every feature, so a
// feature drawn on planes 0, 4, 8 among features drawn on 2 and 6 meets layers it has no
// contour on; left as background there it was cut into one piece per plane, and its surface
// and volume depended on which other features were selected. The slab rule of its own planes
// (each plane's region reaches half way to the feature's next plane) says what it holds there:
// the nearer own plane's contours (ties: the lower plane).
#pragma once

#include <optional>

#include "scansurf/contours.h"
#include "scansurf/grid.h"

namespace scansurf {

// The contour set with, for each feature, a slice on every layer of `grid` strictly between two
// of its consecutive planes, holding the nearer plane's contours; nullopt when no feature
// needs one (the set is used as it is).
std::optional<ContourSet> withOwnSlabs(const ContourSet& contours, const Grid& grid);

}  // namespace scansurf
