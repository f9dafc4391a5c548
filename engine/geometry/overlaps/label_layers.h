// scansurf: label volumes made from each feature's own region (overlap_analysis.h), for the files
// that hold them: every feature's mask in layers (no two features of a layer share a voxel:
// 3D Slicer's layered segmentation), the single partition (one label per voxel, inner features
// first, equal to the GPU's), and their placement on a reference image lattice (the CT).
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/overlaps/overlap_analysis.h"
#include "scansurf/label_volume.h"
#include "scansurf/result.h"

namespace scansurf {

// One volume per mask layer on `grid`: feature f's own voxels carry f's label in layer
// report.features[f].maskLayer.
std::vector<LabelVolume> maskLayerVolumes(const std::vector<FeatureRegion>& regions, const Grid& grid,
                                          const OverlapReport& report);

// One label per voxel: each voxel takes the first feature of `order` (innermost first) whose
// region covers it, exactly as scan conversion labels the volume.
LabelVolume partitionVolume(const std::vector<FeatureRegion>& regions, const Grid& grid, const std::vector<int>& order);

// A volume on the grid cut to the reference lattice it was built on (makeGrid's reference
// grid holds it with a border): same size, origin, spacing and slices as the reference; each
// reference slice takes the grid layer whose slab holds it (nearestLayer).
// `dropped[f]` counts feature f's labelled voxels outside it. Errors: Errc::InvalidArgument
// when the grid does not lie on the reference lattice (other spacing, or an origin off it).
struct ReferenceCut {
  LabelVolume volume;
  std::vector<std::size_t> dropped;  // per feature
};
Result<ReferenceCut> cutToReference(const LabelVolume& volume, const GridReference& reference, std::size_t featureCount);

}  // namespace scansurf
