// scansurf tests: structures that abut in truth but are drawn independently, as two people (or
// two sessions of one) draw neighbours: each outline is its own resampling of the true
// boundary, every point moved along the boundary's normal by up to `jitter`, so neighbours
// overlap by slivers and leave gaps along their interface. All in mm; deterministic per seed.
#pragma once

#include <cstdint>
#include <vector>

#include "scansurf/contours.h"
#include "support/shapes.h"

namespace scansurf {

// A closed path resampled every `step` (from a random phase), each point moved along the path's
// normal by uniform(-jitter, jitter): one drawing of the path.
Contour drawnOutline(const std::vector<Point2>& path, double step, double jitter, ShapeRng& rng);

struct DrawnPelvisOptions {
  double jitter = 1.0;  // mm, each outline point
  std::uint64_t seed = 1;
  bool body = true;             // "BODY" around everything
  bool planningVolume = false;  // "PTV": the prostate with a margin, deep into the rectum
  double pokeDepth = 0;         // > 0: the rectum pokes this far into the prostate, 6 mm wide, on two slices
  double sliceSpacing = 2.0;
};

// "prostate" above and "rectum" below a wavy interface through an ellipsoid (60 x 48 x 28 mm),
// 14 planes (at 2 mm), each drawn on its own: the prostate every 1 mm, the rectum every 1.3 mm.
ContourSet drawnPelvisContours(const DrawnPelvisOptions& options = {});

// Three sectors "a", "b", "c" of a 40 mm disc meeting at its centre (a junction line through
// the stack), eight planes at 2 mm, each sector drawn on its own.
ContourSet drawnSectorsContours(double jitter, std::uint64_t seed);

// "left" and "right": 80 x 40 mm rectangles abutting at x = 0, each reaching `overlap` / 2 past
// it (a long thin overlap along the whole interface), eight planes at 2 mm.
ContourSet thinOverlapContours(double overlap);

}  // namespace scansurf
