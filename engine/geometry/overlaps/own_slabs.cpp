// scansurf: each feature's own slabs on the other features' planes (see own_slabs.h).
#include "geometry/overlaps/own_slabs.h"

#include <algorithm>
#include <vector>

namespace scansurf {
namespace {

// Whether the feature's planes on layers a and b are one of its long gaps.
bool isLongGap(const std::vector<LongGap>& gaps, int feature, int a, int b, const Grid& grid) {
  return std::any_of(gaps.begin(), gaps.end(), [&](const LongGap& g) {
    return g.feature == feature && grid.layerOfPlane(g.below) == a && grid.layerOfPlane(g.above) == b;
  });
}

// The slices to add to feature f (its slices sorted by z, as validation leaves them).
std::vector<FeatureSlice> gapSlices(const Feature& feature, int f, const Grid& grid, const std::vector<LongGap>& gaps) {
  std::vector<FeatureSlice> added;
  int previous = -1;
  const FeatureSlice* previousSlice = nullptr;
  for (const FeatureSlice& slice : feature.slices) {
    const int k = grid.layerOfPlane(slice.z);
    if (k < 0) continue;
    if (previousSlice && k > previous + 1 && !isLongGap(gaps, f, previous, k, grid)) {
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

std::vector<LongGap> longGaps(const ContourSet& contours, const Grid& grid, double gapFactor) {
  std::vector<LongGap> out;
  for (const PlaneGap& g : longPlaneGaps(contours, gapFactor, grid.planeTolerance))
    out.push_back({g, grid.layerOfPlane(g.above) > grid.layerOfPlane(g.below) + 1});
  return out;
}

std::optional<ContourSet> withOwnSlabs(const ContourSet& contours, const Grid& grid, double gapFactor) {
  const std::vector<LongGap> gaps = longGaps(contours, grid, gapFactor);
  std::optional<ContourSet> filled;
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    std::vector<FeatureSlice> added = gapSlices(contours.features[f], static_cast<int>(f), grid, gaps);
    if (added.empty()) continue;
    if (!filled) filled = contours;
    std::vector<FeatureSlice>& slices = filled->features[f].slices;
    slices.insert(slices.end(), std::make_move_iterator(added.begin()), std::make_move_iterator(added.end()));
    std::stable_sort(slices.begin(), slices.end(), [](const FeatureSlice& a, const FeatureSlice& b) { return a.z < b.z; });
  }
  return filled;
}

}  // namespace scansurf
