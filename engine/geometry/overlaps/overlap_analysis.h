// scansurf: overlap analysis and layer assignment. Each feature's own region is rasterized
// exactly as the GPU would draw it alone (pixel_runs.h); pairs whose regions share voxels are
// nested, incidentally overlapping (a sliver between neighbours) or really overlapping;
// features are then coloured into the fewest layers that keep real overlaps apart, abutting
// ones together where possible.
#pragma once

#include <utility>
#include <vector>

#include "geometry/overlaps/pixel_runs.h"
#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/label_volume.h"
#include "scansurf/nesting.h"
#include "scansurf/overlaps.h"

namespace scansurf {

// One feature's own region: per slice, its layer and pixel runs; and its pixel bounding box.
struct FeatureRegion {
  std::vector<int> layers;                                     // sorted, one per slice that lies on the grid
  std::vector<std::vector<PixelRun>> runs;                     // per entry of layers
  int minRow = 0, maxRow = -1, minColumn = 0, maxColumn = -1;  // empty when maxRow < minRow
};

// Calls visit(layer, runsOfA, runsOfB) for each grid layer both regions have; stops when visit
// returns false.
template <typename Visit>
void forEachCommonLayer(const FeatureRegion& a, const FeatureRegion& b, Visit&& visit) {
  for (std::size_t i = 0, j = 0; i < a.layers.size() && j < b.layers.size();) {
    if (a.layers[i] != b.layers[j]) {
      (a.layers[i] < b.layers[j] ? i : j)++;
      continue;
    }
    if (!visit(a.layers[i], a.runs[i], b.runs[j])) return;
    ++i, ++j;
  }
}

// Every feature's region on `grid` (threads: 0 = all).
std::vector<FeatureRegion> rasterizeFeatures(const ContourSet& contours, const Grid& grid, int subPixelBits, int threads);

// Volume of one voxel of layer k (1 .. nz-2): pixel area times the layer's slab.
double voxelVolume(const Grid& grid, int k);

// The slab rule's volume of a feature's contours on the grid: each plane's even-odd area times
// half the distance between its neighbouring layers (FeatureVolumes::contour).
double slabVolume(const Feature& feature, const Grid& grid);

// Volumes three ways, shared and touching pairs, each partial overlap's verdict (incidental or
// real, by `tolerance`: geometry/overlaps/overlap_split.h), and both layer assignments: real overlaps
// apart in the surface layers, any shared voxel apart in the mask layers.
OverlapReport analyzeOverlaps(const ContourSet& contours, const Grid& grid, const Nesting& nesting,
                              const std::vector<FeatureRegion>& regions, const OverlapTolerance& tolerance);

// Colours n features so that no conflicting pair shares a colour, with the fewest colours this
// finds (exact for components of up to 24 features, else DSatur's greedy bound), preferring the
// colour of features it has affinity with. Deterministic.
std::vector<int> assignLayers(int n, const std::vector<std::pair<int, int>>& conflicts,
                              const std::vector<std::pair<int, int>>& affinity);

// Partition mode: for each feature, the voxels of its own region that `partition` gives to
// another feature.
std::vector<VolumeLoss> volumeLosses(const std::vector<FeatureRegion>& regions, const LabelVolume& partition,
                                     const Nesting& nesting);

}  // namespace scansurf
