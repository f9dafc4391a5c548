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
};

struct ContourSet {
  std::string source;        // file name or description, used in error messages
  std::string units = "mm";  // length unit of every coordinate
  std::vector<Feature> features;
  // Nesting order, innermost first, as feature indices; empty = compute it (nestingOrder()).
  std::vector<int> order;
};

// Tolerance (in input units) below which two slice z values are the same plane.
inline constexpr double kDefaultSliceTolerance = 1e-3;

}  // namespace scansurf
