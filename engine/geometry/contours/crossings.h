// scansurf: where a slice's contours cross themselves or each other, and the even-odd area of
// such a slice. Scan conversion fills by the even-odd rule whatever the contours do (paper
// §3.4), so a crossing contour is surfaced as even-odd filling has it; the readers warn about
// it, and the contour volume follows the same rule.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "scansurf/contours.h"

namespace scansurf {

// A point where two edges of the contour that are not neighbours meet (cross or touch), or none.
std::optional<Point2> firstSelfCrossing(const Contour& contour);

// The heights (y) of every point where two edges of the slice's contours meet, the contours'
// own and each other's (neighbouring edges' shared corners left out); sorted, may repeat.
std::vector<double> crossingHeights(std::span<const Contour> contours);

// The area the contours enclose by the even-odd rule, exact for any contours: integrated over
// the strips between consecutive heights of corners and crossings, in each of which the inside
// width is linear in y.
double evenOddArea(std::span<const Contour> contours);

}  // namespace scansurf
