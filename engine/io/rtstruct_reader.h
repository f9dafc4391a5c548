// scansurf: DICOM RT Structure Set (RTSTRUCT) input, read with DCMTK (dcmdata).
//
// Each ROI with CLOSED_PLANAR contours becomes a feature named by its ROI Name, coloured by
// its ROI Display Color. Coordinates stay in DICOM patient space (LPS, mm): a contour point
// (x, y, z) becomes Point2{x, y} on the slice plane z.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/input.h"
#include "scansurf/result.h"

namespace scansurf {

struct RtStructOptions {
  // Glob patterns (*, ?, [...], case-insensitive) selecting ROIs by name; empty = every ROI.
  // A pattern that matches no ROI is an error (Errc::InvalidArgument).
  std::vector<std::string> roiPatterns;
  // Contour z values within this distance (mm) are one slice plane (files carry 12.4999
  // beside 12.5); also the allowed z spread of the points of one contour.
  double sliceTolerance = 0.01;
  // When false, a file without any selected closed contour is not an error (for listing).
  bool requireFeatures = true;
};

struct RtStructure {
  // Validated (validateAndNormalize); slice z snapped to shared planes. Features follow the
  // ROI order, except that ROIs of interpreted type EXTERNAL come last (see rois[].feature).
  ContourSet contours;
  std::vector<RoiInfo> rois;                      // in Structure Set ROI Sequence order
  std::string label;                              // Structure Set Label
  std::string frameOfReferenceUid;                // of the first referenced frame, may be empty
  std::vector<std::string> referencedSeriesUids;  // CT series the contours were drawn on
  std::vector<std::string> warnings;              // skipped contour types, empty ROIs, ...
};

// Reads an RTSTRUCT file (with or without the DICOM Part 10 file header).
// Errors name the file and, where it applies, the ROI and contour:
// Errc::Io when the file cannot be opened; Errc::InvalidInput for a file that is not DICOM,
// DICOM that is not an RT Structure Set, a missing required attribute, contour data whose
// length is not a multiple of 3, a non-finite coordinate, or a contour that is not planar or
// not axial; Errc::InvalidArgument for an ROI pattern that matches nothing.
Result<RtStructure> readRtStruct(const std::filesystem::path& path, const RtStructOptions& options = {});

// True when the file has the DICOM Part 10 preamble ("DICM" at byte 128).
bool hasDicomPreamble(const std::filesystem::path& path);

// Case-insensitive glob match (*, ?, [...]) of a whole name.
bool roiNameMatches(const std::string& pattern, const std::string& name);

// Groups sorted-or-not z values into planes: values within tolerance of a group's lowest
// value join it; each group is represented by its most frequent value (ties: the shortest
// in decimal, then the lowest).
// Returns, for each input value, its plane's z.
std::vector<double> groupSlicePlanes(const std::vector<double>& z, double tolerance);

}  // namespace scansurf
