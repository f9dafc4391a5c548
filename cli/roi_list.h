// scansurf CLI: --list-rois, the ROIs of an RTSTRUCT as a table.
#pragma once

#include <string>
#include <vector>

#include "scansurf/result.h"

namespace scansurf::cli {

// Prints the ROIs of an RTSTRUCT (name, number, type, contours by type, slices, z range,
// whether selected) to stdout.
Result<void> printRoiList(const std::string& path, const std::vector<std::string>& roiPatterns);

}  // namespace scansurf::cli
