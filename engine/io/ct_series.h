// scansurf: the geometry of a CT (or any axial image) series, for --reference: the label
// volume then lies on the CT's voxel lattice (its pixel centres and slice positions).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/result.h"

namespace scansurf {

// All in DICOM patient coordinates (LPS, mm).
struct CtSeries {
  std::string directory;
  std::string seriesUid;
  std::string frameOfReferenceUid;
  std::string modality;
  int columns = 0;      // pixels along x (Columns)
  int rows = 0;         // pixels along y (Rows)
  double spacingX = 0;  // Pixel Spacing [1]: between columns
  double spacingY = 0;  // Pixel Spacing [0]: between rows
  double originX = 0;   // Image Position (Patient) x, y: the centre of the first pixel
  double originY = 0;
  std::vector<double> sliceZ;  // Image Position (Patient) z of each image, increasing
  double sliceThickness = 0;   // Slice Thickness of the first image; 0 when absent
  // Per image, in sliceZ order: its file and SOP Class / SOP Instance UIDs (for references
  // to the images from derived objects such as a DICOM SEG).
  std::vector<std::string> files;
  std::vector<std::string> sopClassUids;
  std::vector<std::string> sopInstanceUids;
};

// Reads the geometry of the one image series in a directory (files that are not DICOM
// images, such as an RTSTRUCT beside the CT, are ignored; subdirectories are not searched).
// Errors (Errc::InvalidInput unless said), naming the file at fault: not a directory (Io); no
// image; more than one series; a missing Image Position / Image Orientation / Pixel Spacing /
// Rows / Columns; an orientation other than axial rows along +x and columns along +y
// (1\0\0\0\1\0); images that differ in size, spacing or in-plane position; two images at
// one z; an image without SOP Instance UID (0008,0018), or two images with the same one.
Result<CtSeries> readCtSeries(const std::filesystem::path& directory);

// The explicit grid reference for makeGrid: the CT's pixel lattice and slice positions.
GridReference gridReferenceOf(const CtSeries& ct);

// Moves every slice of `contours` onto the CT slice within `tolerance` (mm) of it. A slice
// where the series has none (beyond its ends, in a gap where slices are missing, or a series
// of one slice: a partial series, as many plans carry) keeps its z; those z are returned,
// sorted. A slice between two neighbouring CT slices is an error naming the feature, its z
// and the nearest CT z (Errc::InvalidInput): contours drawn between CT slices have no voxel
// layer to go to.
Result<std::vector<double>> placeOnCtSlices(ContourSet& contours, const CtSeries& ct, double tolerance);

}  // namespace scansurf
