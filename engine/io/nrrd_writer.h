// scansurf: the classified label volume as NRRD (teem.sourceforge.net/nrrd/format.html), with
// its geometry, so that it overlays the surfaces in 3D Slicer, ITK-SNAP or ITK; and the
// label-to-feature table beside it.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/label_volume.h"
#include "scansurf/result.h"

namespace scansurf {

// Where the voxels sit in space: voxel (i, j, k) is centred at
// origin + i * axes[0] + j * axes[1] + k * axes[2] (input units).
struct NrrdGeometry {
  std::array<double, 3> origin{};
  std::array<std::array<double, 3>, 3> axes{};  // the step along each index axis
  // NRRD "space": scansurf's contours carry no patient orientation, so their x, y, z are
  // written as DICOM/ITK patient axes (LPS), the convention 3D Slicer also assumes for
  // PLY/OBJ/STL surfaces; a DICOM reader hands in patient coordinates directly.
  std::string space = "left-posterior-superior";
};

// A label volume with a regular geometry, made from a Grid. Layers of a grid may be unevenly
// spaced, which one NRRD spacing cannot express: then the volume is resampled along z onto
// planes spaced by the smallest layer gap from the first layer to the last (at most 8 times as
// many planes as layers; the spacing then grows to fit), each plane taking the labels of the
// nearest layer (`resampled` says so). Evenly spaced layers (within 1e-4 of
// the mean gap, relative) are kept as they are.
struct RegularLabelVolume {
  int nx = 0, ny = 0, nz = 0;
  std::vector<Label> labels;  // x fastest
  NrrdGeometry geometry;
  bool resampled = false;
};
RegularLabelVolume regularize(const LabelVolume& volume);

struct LabelEntry {
  Label label = 0;
  std::string name;
  Rgb color{};
  std::string terminology;  // Slicer's TerminologyEntry (slicer_terminology.h); empty: Tissue
};

// Writes a gzip-encoded NRRD: 3 domain axes, `unsigned char` when every label fits, else
// `unsigned short`, with space directions and origin, plus Slicer segmentation keys
// (SegmentN_Name/Color/LabelValue) so a file named *.seg.nrrd opens as named, coloured
// segments in 3D Slicer. Replaced atomically. Errors: Errc::Io naming the path.
Result<void> writeNrrd(const std::filesystem::path& path, const RegularLabelVolume& volume, const std::vector<LabelEntry>& table);

// The same for a segmentation in layers (3D Slicer's seg.nrrd convention): one layer is a 3-D
// volume; several are a 4-D volume with the list axis first (kinds: list domain domain domain).
// table[s] is in layers[layerOf[s]]; each segment's Extent is the bounding box of its voxels.
Result<void> writeSegmentationNrrd(const std::filesystem::path& path, const std::vector<RegularLabelVolume>& layers,
                                   const std::vector<LabelEntry>& table, const std::vector<int>& layerOf);

// Writes the label table in 3D Slicer's colour-table format (`label name R G B A` per line,
// 0 = background). Replaced atomically. Errors: Errc::Io naming the path.
Result<void> writeLabelTable(const std::filesystem::path& path, const std::vector<LabelEntry>& table);

}  // namespace scansurf
