// scansurf: long gaps in a feature's planes (see plane_gaps.h).
#include "geometry/contours/plane_gaps.h"

#include <algorithm>

namespace scansurf {
namespace {

std::vector<double> planesOf(const Feature& feature, double tolerance) {
  std::vector<double> z;
  for (const FeatureSlice& s : feature.slices) z.push_back(s.z);
  std::sort(z.begin(), z.end());
  std::vector<double> planes;
  for (double v : z)
    if (planes.empty() || v - planes.back() > tolerance) planes.push_back(v);
  return planes;
}

}  // namespace

double medianPlaneGap(const std::vector<double>& planes) {
  std::vector<double> gaps;
  for (std::size_t i = 1; i < planes.size(); ++i) gaps.push_back(planes[i] - planes[i - 1]);
  if (gaps.empty()) return 0;
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  return gaps[gaps.size() / 2];
}

std::vector<PlaneGap> longPlaneGaps(const ContourSet& contours, double gapFactor, double tolerance) {
  std::vector<PlaneGap> out;
  if (!(gapFactor > 0)) return out;
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    const std::vector<double> planes = planesOf(contours.features[f], tolerance);
    const double usual = medianPlaneGap(planes);
    if (!(usual > 0)) continue;
    for (std::size_t i = 1; i < planes.size(); ++i)
      if (planes[i] - planes[i - 1] > gapFactor * usual) out.push_back({static_cast<int>(f), planes[i - 1], planes[i], usual});
  }
  return out;
}

std::vector<double> capLayers(const ContourSet& contours, double gapFactor, double tolerance) {
  std::vector<double> z;
  for (const PlaneGap& g : longPlaneGaps(contours, gapFactor, tolerance))
    z.insert(z.end(), {g.below + g.usual, g.above - g.usual});
  return z;
}

}  // namespace scansurf
