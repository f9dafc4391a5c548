// scansurf: the classified volume (paper §3.4): one integer label per voxel.
#pragma once

#include <cstdint>
#include <vector>

#include "scansurf/grid.h"

namespace scansurf {

using Label = std::uint16_t;
inline constexpr Label kBackground = 0;
// Feature i (index into ContourSet::features) carries label i + 1.
inline constexpr int kMaxFeatures = 65535;
inline Label labelOfFeature(int feature) { return static_cast<Label>(feature + 1); }
inline int featureOfLabel(Label label) { return static_cast<int>(label) - 1; }

struct LabelVolume {
  Grid grid;
  std::vector<Label> labels;  // grid.voxelCount() values, x fastest, then y, then z

  Label at(int i, int j, int k) const { return labels[grid.index(i, j, k)]; }
};

}  // namespace scansurf
