// scansurf CLI: choosing the reader for an input file (contour JSON or DICOM RTSTRUCT),
// --roi / --list-rois, and --reference (a CT series whose lattice the label volume lies on).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/result.h"

namespace scansurf::cli {

struct InputOptions {
  std::vector<std::string> roiPatterns;  // --roi (DICOM only)
  std::string reference;                 // --reference DIR (DICOM only)
};

struct Input {
  ContourSet contours;
  bool dicom = false;
  std::optional<GridReference> reference;  // for BuildOptions::grid.reference
  std::vector<std::string> warnings;       // reader warnings (skipped contours, empty ROIs)
  std::vector<std::string> notes;          // what was read, for the run log
};

// DICOM when the file has the "DICM" preamble, JSON when it is named *.json or starts with
// '{', DICOM otherwise (DCMTK then also reads data sets without a file header).
bool isDicomInput(const std::string& path);

// Reads the input with the right reader; for DICOM applies the ROI selection and, with a
// reference, moves the contours onto its slices. --roi or --reference on JSON input is an
// Errc::InvalidArgument error.
Result<Input> readInput(const std::string& path, const InputOptions& options);

// Prints the ROIs of an RTSTRUCT (name, number, type, contours by type, slices, z range,
// whether selected) to stdout.
Result<void> printRoiList(const std::string& path, const std::vector<std::string>& roiPatterns);

}  // namespace scansurf::cli
