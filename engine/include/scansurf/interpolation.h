// scansurf: interpolated layers between the contour planes (multi-label shape-based
// interpolation; Raya & Udupa 1990, Herman et al. 1992, Grevera & Udupa 1996). Contours drawn
// on slices several pixels thick leave a staircase of one-pixel shelves between planes that
// smoothing cannot cross; interpolated layers let the surface follow the shape instead.
#pragma once

#include <cstdint>

namespace scansurf {

// How a feature closes beyond its first and last contour plane. Both close at half the gap
// to the next layer of the grid (where the surface closed before interpolation existed).
enum class CapShape {
  Flat,   // the end contour extruded half a gap, then a flat lid
  Round,  // a dome half a gap high over the end contour (a quarter ellipse in profile)
};

struct InterpolationOptions {
  // Interpolated layers between two consecutive layers of the grid: factor - 1 of them.
  // kAuto: each gap of at least kAutoMinimum in-plane pixels gets about one layer per pixel
  // (factor = round(gap / pixel), at most kMaxFactor), as long as the volume stays within
  // autoVoxelLimit voxels (the largest factors are lowered until it does, down to
  // kAutoMinimum; below that auto is off); thinner gaps stay as they are. 1: off (only the
  // contour planes, as the seed).
  // Off by default in the library (Engine::build); the command-line tool uses kAuto.
  int factor = 1;
  static constexpr int kAuto = 0;
  static constexpr int kMaxFactor = 16;
  static constexpr int kAutoMinimum = 3;
  std::uint64_t autoVoxelLimit = std::uint64_t{96} << 20;
  // Round by default: closer to round shapes at their poles (a 40 mm sphere in 2 mm slices:
  // 0.041 mm mean distance against 0.059 mm flat). Flat keeps the volume planning systems give
  // a structure (its contours' areas times the slice spacing); round encloses a little less
  // (the phantom's 7-slice target: 5 % less).
  CapShape caps = CapShape::Round;
};

}  // namespace scansurf
