// scansurf: the label volumes a run writes, made from each feature's own region rasterized on
// the CPU exactly as the device scan converted it (geometry/overlaps/label_layers.h): every feature's
// mask in layers (NRRD / seg.nrrd, DICOM SEG) and the single partition (NIfTI), placed on the
// reference CT's own lattice when the contour set has one, else on the grid.
#pragma once

#include <string>
#include <vector>

#include "io/nrrd_writer.h"
#include "scansurf/build_result.h"
#include "scansurf/contours.h"
#include "scansurf/result.h"

namespace scansurf {

struct RunVolumes {
  std::vector<LabelVolume> masksOnGrid;   // mask layers on the build's grid (with its border)
  std::vector<RegularLabelVolume> masks;  // the same as a file holds them
  RegularLabelVolume partition;           // one label per voxel, inner features first (when asked for)
  std::vector<int> maskLayerOf;           // per feature
  std::vector<std::string> warnings;      // voxels of a feature beyond the reference CT
};

// withPartition: also the single partition (for NIfTI); the masks are always made.
Result<RunVolumes> runVolumes(const ContourSet& contours, const BuildResult& built, bool withPartition);

}  // namespace scansurf
