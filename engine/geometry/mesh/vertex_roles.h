// scansurf: the vocabulary smoothing and remeshing share about the multi-label mesh: how a
// vertex may move, and a triangle's label pair as one number.
#pragma once

#include <cstdint>

#include "scansurf/label_volume.h"

namespace scansurf {

// How a vertex may move. Sheet: within its one label pair's sheet. Curve: along a junction
// curve of three or more labels. Plane: on a contour plane's cross-section (smoothing places it
// where the contour crosses its lattice edge; remeshing moves it along the polyline). Corner:
// stays put (curve meeting points, curves crossing a contour plane, polyline branch points,
// junction points smoothing keeps).
enum class VertexRole : std::uint8_t { Sheet, Curve, Plane, Corner };

// A triangle's label pair {a < b} as one number.
inline std::uint32_t labelPairKey(Label a, Label b) { return a | (static_cast<std::uint32_t>(b) << 16); }

}  // namespace scansurf
