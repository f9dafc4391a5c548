// scansurf: interpolated layers between the contour planes (multi-label shape-based
// interpolation; Raya & Udupa 1990, Herman et al. 1992, Grevera & Udupa 1996). Contours drawn
// on slices several pixels thick leave a staircase of one-pixel shelves between planes that
// smoothing cannot cross; interpolated layers let the surface follow the shape instead.
#pragma once

#include <cstdint>

namespace scansurf {

// How a feature closes beyond its first and last contour plane (with interpolation). Both hold
// the volume the slab rule gives the end plane beyond it: its contour's area times half the gap.
enum class CapShape {
  Flat,  // the end contour extruded half a gap, then a flat lid
  // A dome over the end contour that holds a flat half slab's volume and leaves the contour at
  // the feature's taper there (how fast its area shrank over the gap before): half an
  // ellipsoid 3/4 of the gap high where it did not taper, up to a whole gap where its area
  // shrank as fast as it would to vanish on the next plane (docs/method.md, "Caps"); where
  // another feature begins over the end contour on the next plane, flat.
  Round,
};

struct InterpolationOptions {
  // Interpolated layers between two consecutive layers of the grid: factor - 1 of them.
  // kAuto: each gap of at least kAutoMinimum in-plane pixels gets about one layer per pixel
  // (factor = round(gap / pixel), at most kMaxFactor), as long as the volume stays within autoVoxelLimit
  // voxels (the largest factors are lowered until it does, down to kAutoMinimum; below that
  // auto is off). 1: off (only the contour planes, as the seed).
  // Off by default in the library (Engine::build); the command-line tool uses kAuto.
  int factor = 1;
  static constexpr int kAuto = 0;
  static constexpr int kMaxFactor = 16;
  static constexpr int kAutoMinimum = 3;
  std::uint64_t autoVoxelLimit = std::uint64_t{96} << 20;
  // Round by default: rounder at the poles than a flat lid; both keep the slab rule's volume.
  CapShape caps = CapShape::Round;
};

}  // namespace scansurf
