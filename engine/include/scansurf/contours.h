// scansurf: the contour model, the input of the scanline surfacing method
// (Lee, Fletcher, Whitaker et al., "Scanline Surfacing", §3.2): a list of features, each
// with the slices it appears in, each slice with its closed contours.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace scansurf {

struct Point2 {
  double x = 0;
  double y = 0;
};

// A closed polyline; the closing edge is implied (the last point is not a copy of the first).
struct Contour {
  std::vector<Point2> points;
};

// All contours of one feature on one slice plane. They combine by the even-odd rule.
struct FeatureSlice {
  double z = 0;
  std::vector<Contour> contours;
};

using Rgb = std::array<std::uint8_t, 3>;

struct Feature {
  std::string name;
  std::optional<Rgb> color;  // sRGB, when the input gave one
  std::vector<FeatureSlice> slices;
  // Where the file keeps it, for the report and the segment terminology: RTSTRUCT its ROI
  // Number (3006,0022) and RT ROI Interpreted Type (3006,00A4), e.g. ORGAN, PTV, EXTERNAL;
  // IMOD and Reconstruct the object's number (ObjectInfo::number). 0 and empty: not given.
  int sourceNumber = 0;
  std::string interpretedType;
};

// An explicit voxel lattice to lie on, e.g. the CT series the contours were drawn on: pixel
// (i, j) of slice k is centred at (originX + i*spacingX, originY + j*spacingY, sliceZ[k]).
struct GridReference {
  double originX = 0;
  double originY = 0;
  double spacingX = 1;
  double spacingY = 1;
  int nx = 0;
  int ny = 0;
  std::vector<double> sliceZ;  // strictly increasing
};

// What the coordinates are: a patient's (DICOM LPS: x left, y posterior, z superior; RTSTRUCT,
// and contour-set JSON by convention) or a specimen's (an EM series: x and y in the section
// plane, z across the sections; Reconstruct, IMOD). The scene writer names it.
enum class CoordinateFrame { PatientLps, Specimen };

struct ContourSet {
  std::string source;        // file name or description, used in error messages
  std::string units = "mm";  // length unit of every coordinate
  CoordinateFrame frame = CoordinateFrame::PatientLps;
  std::vector<Feature> features;
  // Nesting order, innermost first, as feature indices; empty = compute it (nestingOrder()).
  std::vector<int> order;
  // The image lattice the contours were drawn on, when the reader was given it (RTSTRUCT with
  // a reference CT): build() then puts the label volume on it (BuildOptions::grid).
  std::optional<GridReference> reference;
  // The in-plane box of every feature the file holds, set by a reader that kept only some (ROI
  // or object selection): the default grid takes its pixel size and lattice from it, so that a
  // feature's surface does not depend on which others were selected.
  struct Extent {
    double minX = 0, minY = 0, maxX = 0, maxY = 0;
  };
  std::optional<Extent> fileExtent;
  // Slice z values closer than this are one plane (input units), set by validation from the
  // data itself (sliceToleranceOf); 0 = not validated.
  double planeTolerance = 0;
  // The files the reader read (the input, and a Reconstruct series' section files), for the
  // report's hashes; empty for a set made in memory.
  std::vector<std::string> files;
  // RTSTRUCT: the Frame of Reference UID the contours are drawn in (of the first referenced
  // frame); empty when none.
  std::string frameOfReferenceUid;
  // What the reader skipped or doubted (skipped contour types, empty ROIs) and what it read
  // (one line each), for a run log. Not used by the method.
  std::vector<std::string> warnings;
  std::vector<std::string> notes;
};

// Two slice z values closer than this share of the typical spacing between a feature's own
// planes are one plane, in any unit: 5 nm sections in metres and 2 mm CT slices alike.
inline constexpr double kRelativeSliceTolerance = 1e-3;

// The plane tolerance of a set that carries none (not validated), in input units.
inline constexpr double kDefaultSliceTolerance = 1e-3;

// The slice tolerance a run uses: `requested` when positive, else the set's own
// (ContourSet::planeTolerance), else kDefaultSliceTolerance.
inline double sliceToleranceOf(const ContourSet& contours, double requested = 0) {
  if (requested > 0) return requested;
  return contours.planeTolerance > 0 ? contours.planeTolerance : kDefaultSliceTolerance;
}

}  // namespace scansurf
