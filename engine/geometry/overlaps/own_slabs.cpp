// scansurf: each feature's own slabs on the other features' planes (see own_slabs.h).
#include "geometry/overlaps/own_slabs.h"

#include <algorithm>
#include <vector>

namespace scansurf {
namespace {

// The slices to add to one feature (its slices sorted by z, as validation leaves them).
std::vector<FeatureSlice> gapSlices(const Feature& feature, const Grid& grid) {
  std::vector<FeatureSlice> added;
  int previous = -1;
  const FeatureSlice* previousSlice = nullptr;
  for (const FeatureSlice& slice : feature.slices) {
    const int k = grid.layerOfPlane(slice.z);
    if (k < 0) continue;
    if (previousSlice && k > previous + 1) {
      const double za = grid.layerZ[static_cast<std::size_t>(previous)], zb = grid.layerZ[static_cast<std::size_t>(k)];
      for (int m = previous + 1; m < k; ++m) {
        const double z = grid.layerZ[static_cast<std::size_t>(m)];
        added.push_back({z, z - za <= zb - z ? previousSlice->contours : slice.contours});
      }
    }
    previous = k, previousSlice = &slice;
  }
  return added;
}

}  // namespace

std::optional<ContourSet> withOwnSlabs(const ContourSet& contours, const Grid& grid) {
  std::optional<ContourSet> filled;
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    std::vector<FeatureSlice> added = gapSlices(contours.features[f], grid);
    if (added.empty()) continue;
    if (!filled) filled = contours;
    std::vector<FeatureSlice>& slices = filled->features[f].slices;
    slices.insert(slices.end(), std::make_move_iterator(added.begin()), std::make_move_iterator(added.end()));
    std::stable_sort(slices.begin(), slices.end(), [](const FeatureSlice& a, const FeatureSlice& b) { return a.z < b.z; });
  }
  return filled;
}

}  // namespace scansurf
