// scansurf: the colour of each feature, in one place for every output (GLB, label table,
// preview, report): the input's colour when it gave one, else a distinct default.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/nesting.h"

namespace scansurf {

// Distinct, saturated sRGB colours that read well on a light or dark background; cycled when
// there are more features (after that, features of the same colour are 12 apart).
inline constexpr std::array<Rgb, 12> kDefaultPalette{{
    {230, 159, 0},    // orange
    {86, 180, 233},   // sky blue
    {0, 158, 115},    // bluish green
    {213, 94, 0},     // vermilion
    {204, 121, 167},  // reddish purple
    {240, 228, 66},   // yellow
    {0, 114, 178},    // blue
    {153, 153, 153},  // grey
    {120, 72, 160},   // purple
    {166, 86, 40},    // brown
    {102, 194, 165},  // teal
    {231, 41, 138},   // magenta
}};

// One sRGB colour per feature, in input order.
inline std::vector<Rgb> featureColors(const ContourSet& contours) {
  std::vector<Rgb> colors;
  colors.reserve(contours.features.size());
  for (std::size_t f = 0; f < contours.features.size(); ++f)
    colors.push_back(contours.features[f].color.value_or(kDefaultPalette[f % kDefaultPalette.size()]));
  return colors;
}

// One opacity per feature for display: features that enclose others at `enclosing`, so what
// they hold shows through (preview, GLB), the rest opaque.
inline std::vector<float> displayOpacity(const Nesting& nesting, float enclosing = 0.3f) {
  std::vector<float> opacity(nesting.parent.size(), 1.0f);
  for (int parent : nesting.parent)
    if (parent >= 0) opacity[static_cast<std::size_t>(parent)] = enclosing;
  return opacity;
}

}  // namespace scansurf
