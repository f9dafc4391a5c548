// scansurf: long gaps in a feature's planes. Two consecutive planes farther apart than a
// factor times the feature's median plane spacing are a part left undrawn or a stray contour
// far from the rest; the slab rule would bridge them with a vertical-walled lid, so each side
// is capped on its own instead (own_slabs.h), on layers a usual spacing beyond each plane that
// the grid gets whatever else is drawn (grid.h), so that the caps do not depend on which other
// features are selected.
#pragma once

#include <vector>

#include "scansurf/contours.h"

namespace scansurf {

struct PlaneGap {
  int feature = 0;
  double below = 0, above = 0;  // the planes' z
  double usual = 0;             // the feature's median plane spacing
};

// The median spacing of sorted plane positions (0 for fewer than two).
double medianPlaneGap(const std::vector<double>& planes);

// Every feature's long gaps (gapFactor 0: none), in feature order, then by z; planes closer
// than tolerance are one.
std::vector<PlaneGap> longPlaneGaps(const ContourSet& contours, double gapFactor, double tolerance);

// The layers each long gap needs: below + usual and above - usual.
std::vector<double> capLayers(const ContourSet& contours, double gapFactor, double tolerance);

}  // namespace scansurf
