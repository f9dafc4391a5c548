// scansurf CLI: --list-rois and --list-objects, the ROIs of an RTSTRUCT or the objects of a
// Reconstruct series or IMOD model as a table.
#pragma once

#include <string>
#include <vector>

#include "scansurf/result.h"

namespace scansurf::cli {

// Prints the ROIs of an RTSTRUCT (name, number, type, contours by type, slices, z range,
// whether selected) to stdout.
Result<void> printRoiList(const std::string& path, const std::vector<std::string>& roiPatterns);

// Prints the objects of a Reconstruct series or IMOD model (number, name, contours, skipped
// contours, sections or slices, z range, whether selected) to stdout, and what the reader
// skipped as warnings to stderr.
Result<void> printObjectList(const std::string& path, const std::vector<std::string>& objectPatterns);

}  // namespace scansurf::cli
