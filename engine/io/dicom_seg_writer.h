// scansurf: the label volume as a DICOM Segmentation (PS3.3 A.51) on the reference CT's own
// grid, written with DCMTK's dcmseg (and its dcmfg / dcmiod helpers).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/ct_series.h"
#include "scansurf/contours.h"
#include "scansurf/label_volume.h"
#include "scansurf/outputs.h"
#include "scansurf/result.h"

namespace scansurf {

// Writes a BINARY Segmentation: Rows, Columns, Pixel Spacing and slice positions are the CT's
// (`ct`, from readCtSeries); the label volumes (mask layers: each feature's own voxels in one
// of them, so segments may overlap as the structures do) must lie on the CT's lattice (the grid makeGrid
// builds from gridReferenceOf(ct): one background voxel around the CT, so CT voxel (i, j, k)
// is grid voxel (i + 1, j + 1, k + 1) unless the contours reached beyond the CT). Feature f's
// segment holds the voxels labelled f + 1 in its layer: its own region, whatever overlaps it. One segment per feature with at
// least one voxel inside the CT (label = its name, Recommended Display CIELab Value = its colour, algorithm AUTOMATIC "scansurf",
// category and type SCT 85756007 "Tissue"); one frame per segment and CT slice that holds
// some of it (empty frames are left out), with Plane Position, Frame Content (dimension
// indices: segment number, slice position) and Derivation Image (source: that CT image) per
// frame and Plane Orientation and Pixel Measures shared. Patient, study and frame of
// reference are imported from the first CT image; Referenced Series Sequence lists every
// CT image. Replaced atomically.
// Errors: Errc::InvalidArgument when the volume is not on the CT lattice; Errc::InvalidInput
// when no feature has a voxel inside the CT or a CT image cannot be read; Errc::Internal when
// DCMTK refuses the object (its message is kept); Errc::Io naming the path.
Result<DicomSegSummary> writeDicomSegmentation(const std::filesystem::path& path, const ContourSet& contours,
                                               const std::vector<LabelVolume>& layers, const CtSeries& ct);

}  // namespace scansurf
