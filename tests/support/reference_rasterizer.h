// CPU reference of the GPU scan conversion (engine/passes/scan_conversion.cpp), bit for bit:
// the same sub-pixel snapping (geometry/overlaps/raster_rules.h), triangle fans from each contour's
// first point, Vulkan's top-left tie-breaking rule at pixel centres, even-odd parity per
// feature and slice, and the lowest nesting rank winning.
#pragma once

#include <vector>

#include "scansurf/contours.h"
#include "scansurf/label_volume.h"

namespace scansurf::test {

LabelVolume referenceScanConvert(const ContourSet& contours, const Grid& grid, const std::vector<int>& order, int subPixelBits);

}  // namespace scansurf::test
