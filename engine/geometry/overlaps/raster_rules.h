// scansurf: the pixel-centre rule of scan conversion, shared by the GPU pass and the CPU
// reference so that both see the same numbers.
//
// Voxel (i, j) of a layer is centred at (originX + i*spacingX, originY + j*spacingY). In the
// framebuffer, pixel (i, j) spans [i, i+1) x [j, j+1) and is sampled at its centre
// (i + 0.5, j + 0.5), so a contour point maps to u = (x - originX)/spacingX + 0.5 and
// v = (y - originY)/spacingY + 0.5. Points are snapped (round to nearest) to the device's
// sub-pixel grid of 2^-subPixelBits pixel before drawing, exactly as the rasterizer would.
// A pixel belongs to a feature when its centre is inside the feature's contours by the
// even-odd rule; a centre exactly on an edge follows Vulkan's tie-breaking rule (the
// top-left rule on the devices we know), which gives a centre on an edge shared by two
// abutting features to exactly one of them.
#pragma once

#include <cmath>
#include <cstdint>

#include "scansurf/grid.h"

namespace scansurf {

struct SubpixelPoint {
  std::int64_t u = 0;  // framebuffer x in units of 2^-bits pixel
  std::int64_t v = 0;
};

inline SubpixelPoint toSubpixel(const Grid& grid, double x, double y, int subPixelBits) {
  const double scale = std::ldexp(1.0, subPixelBits);
  return {std::llround(((x - grid.originX) / grid.spacingX + 0.5) * scale),
          std::llround(((y - grid.originY) / grid.spacingY + 0.5) * scale)};
}

// Smallest power of two >= n: the viewport size that makes pixel -> NDC -> pixel exact.
inline std::uint32_t viewportExtent(int n) {
  std::uint32_t p = 1;
  while (p < static_cast<std::uint32_t>(n)) p <<= 1;
  return p;
}

// Depth of the feature with nesting rank `rank` (0 = innermost) among `count` features:
// inside (0, 1), increasing with rank, so the depth test LESS lets inner features win.
inline float rankDepth(int rank, int count) { return static_cast<float>(rank + 1) / static_cast<float>(count + 2); }

}  // namespace scansurf
