// scansurf: reading contour sets, whatever the file: the contour-set JSON
// (docs/input-format.md) or a DICOM RT Structure Set, recognised by content.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/result.h"

namespace scansurf {

enum class InputFormat { ContoursJson, RtStruct };

struct ReadOptions {
  // RTSTRUCT: glob patterns (*, ?, [...], case-insensitive) selecting ROIs by name; empty =
  // every ROI. A pattern that matches no ROI is Errc::InvalidArgument.
  std::vector<std::string> roiPatterns;
  // RTSTRUCT: a folder holding the CT (or other axial image) series the contours were drawn
  // on. The contours are moved onto its slices and ContourSet::reference is set, so build()
  // puts the label volume on the CT's voxel lattice. Empty = none.
  std::filesystem::path referenceSeries;
};

// The format of a file by its content: DICOM when it has the "DICM" preamble; JSON when it is
// named *.json or starts with '{'; DICOM otherwise (data sets without a file header).
InputFormat detectInputFormat(const std::filesystem::path& path);

// Reads and validates a contour set. source is the path as given; warnings and notes say what
// was skipped and read. Errors name the file and, where it applies, the feature (ROI), slice
// and contour: Errc::Io (cannot read), Errc::InvalidInput (malformed or inconsistent content),
// Errc::InvalidArgument (ROI selection or reference series given for JSON input, or a
// pattern that matches nothing), Errc::OutOfMemory.
Result<ContourSet> readContours(const std::filesystem::path& path, const ReadOptions& options = {});

// One ROI of a structure set as the file holds it.
struct RoiInfo {
  int number = 0;               // ROI Number (3006,0022)
  std::string name;             // ROI Name (3006,0026)
  std::string interpretedType;  // RT ROI Interpreted Type (3006,00A4), e.g. EXTERNAL, ORGAN; may be empty
  std::optional<Rgb> color;     // ROI Display Color (3006,002A)
  std::map<std::string, int> contoursByType;  // Contour Geometric Type -> count
  int slices = 0;               // distinct planes of its CLOSED_PLANAR contours
  double zMin = 0;              // z range of all its contour points (mm); valid when any
  double zMax = 0;
  bool selected = true;         // matched by the ROI patterns
  int feature = -1;             // index of its feature among the surfaced ones, or -1
};

struct StructureSetInfo {
  std::string label;           // Structure Set Label
  std::vector<RoiInfo> rois;   // in Structure Set ROI Sequence order
};

// The ROIs of an RTSTRUCT file, with whether `roiPatterns` select each; a file with nothing
// to surface is not an error here. Errors: as readContours; JSON input is Errc::InvalidArgument.
Result<StructureSetInfo> listRois(const std::filesystem::path& path, const std::vector<std::string>& roiPatterns = {});

// One object of a Reconstruct series or an IMOD model as the file holds it.
struct ObjectInfo {
  int number = 0;             // IMOD: object number (1-based); Reconstruct: position in the list (1-based)
  std::string name;           // as surfaced (IMOD: "object N" when unnamed; "#N" added to a repeated name)
  std::optional<Rgb> color;   // Reconstruct: its first trace's border colour; IMOD: the object colour
  int contours = 0;           // closed contours read (the ones surfaced when selected)
  int skipped = 0;            // contours not surfaced: open traces, open or scattered objects, degenerate
  int slices = 0;             // distinct planes (sections) of its closed contours
  double zMin = 0;            // z range of its closed contours (ContourSet units); valid when slices > 0
  double zMax = 0;
  bool selected = true;       // matched by the object patterns
  int feature = -1;           // index of its feature among the surfaced ones, or -1
};

// Writes a contour set as contour-set JSON version 1 (every double written so it reads back
// exactly), staged and renamed so a failure leaves no partial file. Errors:
// Errc::InvalidArgument for a non-finite value or an order index out of range; Errc::Io.
Result<void> writeContours(const ContourSet& contours, const std::filesystem::path& path);

}  // namespace scansurf
