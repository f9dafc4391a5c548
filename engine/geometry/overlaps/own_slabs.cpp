// scansurf: each feature's own slabs on the other features' planes (see own_slabs.h).
#include "geometry/overlaps/own_slabs.h"

#include <algorithm>
#include <vector>

#include "geometry/contours/plane_gaps.h"

namespace scansurf {
namespace {

// The feature's planes on the grid: (layer, slice) in z order.
std::vector<std::pair<int, const FeatureSlice*>> planesOf(const Feature& feature, const Grid& grid) {
  std::vector<std::pair<int, const FeatureSlice*>> planes;
  for (const FeatureSlice& slice : feature.slices)
    if (const int k = grid.layerOfPlane(slice.z); k >= 0) planes.push_back({k, &slice});
  return planes;
}

double medianGap(const std::vector<std::pair<int, const FeatureSlice*>>& planes) {
  std::vector<double> z;
  for (const auto& [k, slice] : planes) z.push_back(slice->z);
  return medianPlaneGap(z);
}

bool isLong(double gap, double usual, double gapFactor) { return gapFactor > 0 && usual > 0 && gap > gapFactor * usual; }

// The slices to add to one feature (its slices sorted by z, as validation leaves them).
std::vector<FeatureSlice> gapSlices(const Feature& feature, const Grid& grid, double gapFactor) {
  const auto planes = planesOf(feature, grid);
  const double usual = medianGap(planes);
  std::vector<FeatureSlice> added;
  for (std::size_t i = 1; i < planes.size(); ++i) {
    const auto [previous, previousSlice] = planes[i - 1];
    const auto [k, slice] = planes[i];
    if (k <= previous + 1 || isLong(slice->z - previousSlice->z, usual, gapFactor)) continue;
    const double za = grid.layerZ[static_cast<std::size_t>(previous)], zb = grid.layerZ[static_cast<std::size_t>(k)];
    for (int m = previous + 1; m < k; ++m) {
      const double z = grid.layerZ[static_cast<std::size_t>(m)];
      added.push_back({z, z - za <= zb - z ? previousSlice->contours : slice->contours});
    }
  }
  return added;
}

}  // namespace

std::vector<LongGap> longGaps(const ContourSet& contours, const Grid& grid, double gapFactor) {
  std::vector<LongGap> out;
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    const auto planes = planesOf(contours.features[f], grid);
    const double usual = medianGap(planes);
    for (std::size_t i = 1; i < planes.size(); ++i) {
      const double below = planes[i - 1].second->z, above = planes[i].second->z;
      if (isLong(above - below, usual, gapFactor))
        out.push_back({static_cast<int>(f), below, above, usual, planes[i].first > planes[i - 1].first + 1});
    }
  }
  return out;
}

std::optional<ContourSet> withOwnSlabs(const ContourSet& contours, const Grid& grid, double gapFactor) {
  std::optional<ContourSet> filled;
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    std::vector<FeatureSlice> added = gapSlices(contours.features[f], grid, gapFactor);
    if (added.empty()) continue;
    if (!filled) filled = contours;
    std::vector<FeatureSlice>& slices = filled->features[f].slices;
    slices.insert(slices.end(), std::make_move_iterator(added.begin()), std::make_move_iterator(added.end()));
    std::stable_sort(slices.begin(), slices.end(), [](const FeatureSlice& a, const FeatureSlice& b) { return a.z < b.z; });
  }
  return filled;
}

}  // namespace scansurf
