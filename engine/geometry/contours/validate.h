// scansurf: model-level checks shared by every reader (JSON, later DICOM RTSTRUCT).
#pragma once

#include <string>

#include "scansurf/contours.h"
#include "scansurf/result.h"

namespace scansurf {

// Coordinates farther from the origin than this (input units: 10 km in mm, 10 m in µm) are
// refused: float32 surface positions could not resolve a voxel there, and no anatomy or
// specimen is that large.
inline constexpr double kMaxCoordinate = 1e7;

// Checks a freshly read contour set and normalizes it in place:
// - drops consecutive duplicate points and a repeated closing point;
// - sets planeTolerance (kRelativeSliceTolerance of the median spacing of the features' own
//   planes), moves every slice within it of a lower plane onto that plane, across features
//   (with a warning), and merges each feature's slices of one plane (their contours combine).
// Errors (Errc::InvalidInput), each naming contours.source and the feature, slice and contour
// at fault: no features; more than kMaxFeatures; an empty or duplicate feature name, a NUL in a
// name or in the units; a
// non-finite z or coordinate, or one beyond kMaxCoordinate; a contour of fewer than 3 distinct points; a slice without
// contours; an `order` that does not name every feature exactly once.
Result<void> validateAndNormalize(ContourSet& contours);

// Message prefixes in the shared format, e.g. `phantom.json: feature "rectum" (#3)`.
std::string describeFeature(const ContourSet& contours, int feature);
std::string describeSlice(const ContourSet& contours, int feature, int slice, double z);

// Shortest text that reads back as the same double (12.5, not 12.500000).
std::string formatNumber(double value);

}  // namespace scansurf
