// scansurf: reading contour sets, whatever the file: the contour-set JSON
// (docs/input-format.md), a DICOM RT Structure Set, a Reconstruct series (serial-section EM
// tracing, XML) or an IMOD binary model, recognised by content.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/result.h"

namespace scansurf {

enum class InputFormat {
  ContoursJson,        // scansurf's contour-set JSON
  RtStruct,            // DICOM RT Structure Set, with or without the Part 10 file header
  ReconstructSeries,   // Reconstruct XML: a series file (.ser) or one of its section files
  ImodModel,           // IMOD binary model (.mod)
  SlicerSegmentation,  // 3D Slicer planar-contour segmentation (.seg.vtm, or one segment's .vtp)
  Unknown,             // none of these (or an empty or unreadable file)
};

// A short name of the format ("DICOM RTSTRUCT", "IMOD model", ...).
const char* inputFormatName(InputFormat format) noexcept;

struct ReadOptions {
  // RTSTRUCT: glob patterns (*, ?, [...], case-insensitive) selecting ROIs by name; empty =
  // every ROI. A pattern that matches no ROI is Errc::InvalidArgument.
  std::vector<std::string> roiPatterns;
  // RTSTRUCT: a folder holding the CT (or other axial image) series the contours were drawn
  // on. The contours are moved onto its slices and ContourSet::reference is set, so build()
  // puts the label volume on the CT's voxel lattice. Empty = none.
  std::filesystem::path referenceSeries;
  // Reconstruct and IMOD: glob patterns (as roiPatterns) selecting objects by name; empty =
  // every object. A pattern that matches no object is Errc::InvalidArgument.
  std::vector<std::string> objectPatterns;
};

// The format of a file by its content, never by its name alone: DICOM when it has the "DICM"
// preamble, or when it starts with a plausible data element (a data set without the Part 10
// header: group 0002 or 0008, little endian, implicit or explicit VR); IMOD when it starts
// with "IMOD"; Reconstruct when it is XML whose root element is <Series> or <Section>; JSON
// when it starts with '{' (after white space) or is named *.json; Unknown otherwise.
InputFormat detectInputFormat(const std::filesystem::path& path);

// Reads and validates a contour set. source is the path as given; warnings and notes say what
// was skipped and read. Coordinates are in ContourSet::units: mm for RTSTRUCT, the series'
// units for Reconstruct, the model's units for IMOD. Errors name the file and, where it
// applies, the feature (ROI, object), section or slice, and contour: Errc::Io (cannot read),
// Errc::InvalidInput (an unrecognised format, listing the supported ones; malformed or
// inconsistent content), Errc::InvalidArgument (ROI or object selection or a reference
// series given for a format they do not apply to, or a pattern that matches nothing),
// Errc::OutOfMemory.
Result<ContourSet> readContours(const std::filesystem::path& path, const ReadOptions& options = {});

// Checks a contour set made in memory as readContours checks a file's, and normalizes it in
// place: repeated points and contours dropped (with a warning), slices sorted, the plane
// tolerance set (ContourSet::planeTolerance) and slices within it merged onto shared planes.
// Errors: Errc::InvalidInput naming contours.source and the feature, slice, contour and point
// at fault (no features, an empty or duplicate name, a non-finite or far coordinate, a contour
// of fewer than 3 distinct points, a slice without contours, an order that does not name every
// feature once). Engine::build validates a copy of any set that has not been validated.
Result<void> validateContours(ContourSet& contours);

// One ROI of a structure set as the file holds it.
struct RoiInfo {
  int number = 0;                             // ROI Number (3006,0022)
  std::string name;                           // ROI Name (3006,0026)
  std::string interpretedType;                // RT ROI Interpreted Type (3006,00A4), e.g. EXTERNAL, ORGAN; may be empty
  std::optional<Rgb> color;                   // ROI Display Color (3006,002A)
  std::map<std::string, int> contoursByType;  // Contour Geometric Type -> count
  int slices = 0;                             // distinct planes of its CLOSED_PLANAR contours
  double zMin = 0;                            // z range of all its contour points (mm); valid when any
  double zMax = 0;
  bool selected = true;  // matched by the ROI patterns
  int feature = -1;      // index of its feature among the surfaced ones, or -1
};

struct StructureSetInfo {
  std::string label;          // Structure Set Label
  std::vector<RoiInfo> rois;  // in Structure Set ROI Sequence order
};

// The ROIs of an RTSTRUCT file (or the segments of a 3D Slicer segmentation, numbered in file
// order, with no label), with whether `roiPatterns` select each; a file with nothing to
// surface is not an error here. Errors: as readContours; JSON input is Errc::InvalidArgument.
Result<StructureSetInfo> listRois(const std::filesystem::path& path, const std::vector<std::string>& roiPatterns = {});

// One object of a Reconstruct series or an IMOD model as the file holds it.
struct ObjectInfo {
  int number = 0;            // IMOD: object number (1-based); Reconstruct: position in the list (1-based)
  std::string name;          // as surfaced (IMOD: "object N" when unnamed; "#N" added to a repeated name)
  std::optional<Rgb> color;  // Reconstruct: its first trace's border colour; IMOD: the object colour
  int contours = 0;          // closed contours read (the ones surfaced when selected)
  int skipped = 0;           // contours not surfaced: open traces, open or scattered objects, degenerate
  int slices = 0;            // distinct planes (sections) of its closed contours
  double zMin = 0;           // z range of its closed contours (ContourSet units); valid when slices > 0
  double zMax = 0;
  bool selected = true;  // matched by the object patterns
  int feature = -1;      // index of its feature among the surfaced ones, or -1
};

struct ObjectListing {
  InputFormat format = InputFormat::Unknown;
  std::string description;            // e.g. `Reconstruct series "cells" (12 sections)`
  std::string units;                  // of z and of every coordinate
  std::vector<ObjectInfo> objects;    // Reconstruct: by name; IMOD: in model order
  std::vector<std::string> warnings;  // what the reader skipped
};

// The objects of a Reconstruct series or IMOD model, with whether `objectPatterns` select
// each; a file with nothing to surface is not an error here. Errors: as readContours; other
// formats are Errc::InvalidArgument.
Result<ObjectListing> listObjects(const std::filesystem::path& path, const std::vector<std::string>& objectPatterns = {});

// Writes a contour set as contour-set JSON version 1 (every double written so it reads back
// exactly), staged and renamed so a failure leaves no partial file. Errors:
// Errc::InvalidArgument for a non-finite value or an order index out of range; Errc::Io.
Result<void> writeContours(const ContourSet& contours, const std::filesystem::path& path);

}  // namespace scansurf
