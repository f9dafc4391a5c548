// scansurf: Reconstruct series input (J. C. Fiala, "Reconstruct: a free editor for serial
// section microscopy", J. Microscopy 218:52-61, 2005; the XML series and section files of
// Reconstruct 1.1, as PyReconstruct still imports them). Parsed with pugixml.
//
// A series NAME.ser (units, zMidSection) has its sections in NAME.1, NAME.2, ... beside it.
// Each section (index, thickness) holds Transform elements; a Transform holds either an Image
// with its domain outline (image pixels; not an object) or traces (Contour elements) whose
// points are in the series' units. Every closed trace is a contour of the object it names,
// hidden or not (hidden is a display state); open traces are skipped. The trace points are
// stored through their Transform: a section point p is stored as T(p), so the reader applies
// the inverse, as Reconstruct does when it draws or exports them (Contour::InvNform).
//
// z of a section: Reconstruct's own section depth (SectionsInfo::ZDistance): the thicknesses
// of every present section with a lower index (section 0 excepted) plus its own thickness, or
// half of it when the series sets zMidSection. Uneven thickness and missing section numbers
// come out as Reconstruct's 3D scene and exports place them; index x thickness would not.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/input.h"
#include "scansurf/result.h"

namespace scansurf {

// A Reconstruct Transform: dim 0-6 and the coefficients xcoef = a, ycoef = b of
//   x' = a0 + a1 x + a2 y + a3 x y + a4 x^2 + a5 y^2   (y' likewise with b),
// of which dim says how many are used: 0 identity; 1 translation (x' = a0 + x,
// y' = b0 + y); 2 translation and scale (x' = a0 + a1 x, y' = b0 + b1 y: here b1 scales y);
// 3 affine (a0..a2, b0..b2); 4 adds x y; 5 adds x^2; 6 adds y^2.
struct ReconstructTransform {
  int dim = 0;
  std::array<double, 6> a{0, 1, 0, 0, 0, 0};  // as the general polynomial above (dim applied)
  std::array<double, 6> b{0, 0, 1, 0, 0, 0};

  // From the file's dim and coefficient lists (missing coefficients count as 0). Errors
  // (Errc::InvalidInput, message without location): dim outside 0-6, a non-finite coefficient.
  static Result<ReconstructTransform> fromFile(int dim, const std::vector<double>& xcoef, const std::vector<double>& ycoef);

  Point2 forward(Point2 p) const;
  // The section point stored as q: exact for dim 0-3, Newton's method from the affine part's
  // inverse for dim 4-6 (converged to 1e-12 relative, or an error). Errors
  // (Errc::InvalidInput, message without location): a singular transform at q.
  Result<Point2> inverse(Point2 q) const;
};

struct ReconstructOptions {
  std::vector<std::string> objectPatterns;  // glob, case-insensitive; empty = every object
  bool requireFeatures = true;              // false: nothing to surface is not an error (listing)
};

struct ReconstructSeries {
  ContourSet contours;               // validated; units from the series; z per section as above
  std::vector<ObjectInfo> objects;   // by name
  std::string name;                  // series name (file stem)
  std::filesystem::path seriesFile;  // NAME.ser, empty when absent
  int sections = 0;
  int firstIndex = 0, lastIndex = 0;
  bool zMidSection = false;
};

// Reads a series from its .ser file or from any of its section files (the whole series is
// read either way; a section file without a .ser beside it is read with Reconstruct's
// defaults, microns and zMidSection off, and a warning). Errors name the file and, where it
// applies, the section, trace (name and position in the section) and point:
// Errc::Io (cannot read a file), Errc::InvalidInput (malformed XML with its line, a missing
// or bad attribute, a duplicate section index, a singular transform, no section files),
// Errc::InvalidArgument (an object pattern that matches nothing).
Result<ReconstructSeries> readReconstructSeries(const std::filesystem::path& path, const ReconstructOptions& options = {});

// True when the file is XML whose root element is Series or Section (a light check of its
// first kilobytes, for format detection).
bool looksLikeReconstructXml(const std::filesystem::path& path);

}  // namespace scansurf
