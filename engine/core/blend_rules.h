// scansurf: the rules of shape-based interpolation across contour planes that the interpolated
// layers (geometry/interpolation) and the vertices placed between planes without layers
// (geometry/smoothing/plane_blend.h) share, so that both blend and cap a structure alike:
// the monotone cubic Hermite blend (Fritsch & Butland's tangents), which gaps count as alike,
// and the round cap's profile.
#pragma once

#include <algorithm>
#include <cmath>

namespace scansurf {

// The monotone tangent at a plane between the changes before and after it (per gap): their
// harmonic mean, 0 where they differ in sign or one is 0.
inline double monotoneTangent(double before, double after) {
  return before * after > 0 ? 2 * before * after / (before + after) : 0.0;
}

// The Hermite blend at t in [0, 1] of the values a, b on two planes with tangents ta, tb (change
// per gap): the linear blend plus t(1 - t)((1 - t)(ta - c) - t(tb - c)), c = b - a.
inline double hermiteBlend(double a, double b, double ta, double tb, double t) {
  const double chord = b - a;
  return (1 - t) * a + t * b + t * (1 - t) * ((1 - t) * (ta - chord) - t * (tb - chord));
}

// Whether a neighbouring gap is alike in length to `gap`: within a quarter of it either way,
// where the same tangents fit both sides of their common plane.
inline bool alikeGaps(double gap, double other) { return other >= 0.8 * gap && other <= 1.25 * gap; }

// How fast a structure's area shrank toward its end plane over the gap before, per cap gap, as a
// share of its area there, clamped to [0, 1]; a taper beyond 1 (the structure ends within the
// gap) falls back linearly to 0 by 1.25. 0 where it grew.
inline double taperOfAreas(double areaBefore, double areaAtEnd, double capGap, double gapBefore) {
  if (areaAtEnd <= 0 || areaBefore <= areaAtEnd) return 0;
  const double taper = (areaBefore - areaAtEnd) / areaAtEnd * capGap / gapBefore;
  return std::clamp(std::min(taper, 5 - 4 * taper), 0.0, 1.0);
}

// A round cap's profile: at height s over its end plane (in gaps), u = s / height, it keeps
// f = 1 - slope u - (1 - slope) u^2 of the end region's area, which falls from 1 to 0 on [0, 1]
// and holds half a gap of it for any taper a in [0, 1] (height = 6 / (4 + sqrt(16 - 12 a)),
// slope = a height). Taper 0 is half an ellipsoid 3/4 of the gap high; a paraboloid (taper 1)
// stands a whole gap high.
struct RoundCapProfile {
  double height = 0.75;  // in gaps
  double slope = 0;
};
inline RoundCapProfile roundCapProfile(double taper) {
  const double height = 6 / (4 + std::sqrt(16 - 12 * taper));
  return {height, taper * height};
}

}  // namespace scansurf
