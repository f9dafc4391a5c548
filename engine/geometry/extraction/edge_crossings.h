// scansurf: where the original contours cross the in-plane grid edges of a volume of contour
// planes. Shape-based interpolation measures its distances from these crossings, not from
// pixel centres, so the interpolated layers keep the contours' sub-pixel positions (the
// contour planes' own vertices sit there too: geometry/smoothing/contour_fit.h).
#pragma once

#include <cstdint>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/label_volume.h"

namespace scansurf {

// Per voxel of `volume` (scan converted from `contours`): low byte, where a contour crosses
// the edge to the +x neighbour, high byte, to the +y neighbour, in 1/256 of the edge from this
// voxel, for edges whose two labels differ; kMidEdge where no contour of a feature of either
// label (or else of any feature) crosses. Deterministic for any thread count.
// With `medial`, an edge between the two features of an incidental pair crosses at their
// medial line (geometry/overlaps/overlap_split.h), as contour fitting places it.
inline constexpr std::uint8_t kMidEdge = 128;
class MedialCrossings;
std::vector<std::uint16_t> planeEdgeCrossings(const LabelVolume& volume, const ContourSet& contours, int threads,
                                              const MedialCrossings* medial = nullptr);

}  // namespace scansurf
