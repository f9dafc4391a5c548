// scansurf: coverage of contours by pixel centres (see coverage.h). Each candidate row is
// intersected with the contour once, so a large contour costs O(edges) per row and usually
// stops at its first row.
#include "geometry/grid/coverage.h"

#include <algorithm>
#include <cmath>

#include "geometry/contours/polygon.h"
#include "geometry/contours/validate.h"

namespace scansurf {

bool coversPixelCentre(const Contour& contour, const Grid& grid) {
  const Box2 box = boundingBox(contour);
  if (box.empty() || grid.nx <= 0 || grid.ny <= 0) return false;
  auto centreX = [&](int i) { return grid.originX + i * grid.spacingX; };
  auto centreY = [&](int j) { return grid.originY + j * grid.spacingY; };
  // Index range of centres within the box; a one-index margin absorbs rounding.
  const int j0 = std::max(0, static_cast<int>(std::floor((box.minY - grid.originY) / grid.spacingY)) - 1);
  const int j1 = std::min(grid.ny - 1, static_cast<int>(std::ceil((box.maxY - grid.originY) / grid.spacingY)) + 1);
  const int i0 = std::max(0, static_cast<int>(std::floor((box.minX - grid.originX) / grid.spacingX)) - 1);
  const int i1 = std::min(grid.nx - 1, static_cast<int>(std::ceil((box.maxX - grid.originX) / grid.spacingX)) + 1);
  if (j0 > j1 || i0 > i1) return false;

  const auto& pts = contour.points;
  const std::size_t n = pts.size();
  std::vector<double> xs;
  for (int j = j0; j <= j1; ++j) {
    const double y = centreY(j);
    if (y < box.minY || y > box.maxY) continue;
    xs.clear();
    for (std::size_t a = n - 1, b = 0; b < n; a = b++)
      if ((pts[a].y > y) != (pts[b].y > y)) xs.push_back(edgeCrossingX(pts[a], pts[b], y));
    std::sort(xs.begin(), xs.end());
    // A centre x is inside when an odd number of crossings lie strictly right of it, i.e.
    // xs[2k] <= x < xs[2k+1].
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      const double lo = xs[k], hi = xs[k + 1];
      int i = std::max(i0, static_cast<int>(std::ceil((lo - grid.originX) / grid.spacingX)) - 1);
      while (i <= i1 && centreX(i) < lo) ++i;
      if (i <= i1 && centreX(i) < hi) return true;
    }
  }
  return false;
}

std::vector<std::string> findUncoveredContours(const ContourSet& contours, const Grid& grid) {
  std::vector<std::string> messages;
  for (int f = 0; f < static_cast<int>(contours.features.size()); ++f) {
    const Feature& feature = contours.features[f];
    for (int s = 0; s < static_cast<int>(feature.slices.size()); ++s) {
      const FeatureSlice& slice = feature.slices[s];
      for (int c = 0; c < static_cast<int>(slice.contours.size()); ++c)
        if (!coversPixelCentre(slice.contours[c], grid))
          messages.push_back(describeSlice(contours, f, s, slice.z) + ", contour " + std::to_string(c) +
                             ": covers no pixel centre of the grid (spacing " + formatNumber(grid.spacingX) + " x " +
                             formatNumber(grid.spacingY) + "); it will not appear in the volume");
    }
  }
  return messages;
}

}  // namespace scansurf
