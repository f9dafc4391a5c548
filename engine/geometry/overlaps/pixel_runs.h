// scansurf: exact CPU rasterization of one feature's contours on one slice, pixel for pixel
// what the GPU scan conversion draws (Lee et al., "Scanline Surfacing", §3.4), as runs of
// pixels per row. Used where each feature's own region is needed on the CPU: overlap analysis,
// volume accounting and the per-feature masks of the label volume.
//
// The GPU draws triangle fans into an even-odd stencil with Vulkan's top-left rule after
// snapping to 2^-bits pixel (raster_rules.h). Its coverage parity at a pixel centre equals the
// polygon's even-odd parity at the centre displaced by (+e, +e^2) for infinitesimal e: a centre
// on a left or top edge is inside, on a right or bottom edge outside. Casting the scanline
// through the centre, with an edge counted when its lower end is at or above the row (half-open
// in v) and when it crosses at or left of the centre, gives exactly that parity in integers.
#pragma once

#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"

namespace scansurf {

// Pixels [begin, end) of row `row` of one layer.
struct PixelRun {
  int row = 0;
  int begin = 0;
  int end = 0;
};

// The pixels whose centres the contours enclose (even-odd), clipped to the grid; runs sorted
// by row, then begin, never touching one another.
std::vector<PixelRun> rasterizeSlice(const std::vector<Contour>& contours, const Grid& grid, int subPixelBits);

// Pixels in both run lists (each sorted as rasterizeSlice returns them).
std::size_t sharedPixels(const std::vector<PixelRun>& a, const std::vector<PixelRun>& b);

// The pixels in both run lists, as runs sorted as rasterizeSlice returns them.
std::vector<PixelRun> intersectPixelRuns(const std::vector<PixelRun>& a, const std::vector<PixelRun>& b);

// Whether the pixel (column, row) is in the runs (sorted as rasterizeSlice returns them).
bool coversPixel(const std::vector<PixelRun>& runs, int column, int row);

// Whether a pixel of `a` and one of `b` share an edge in the plane (same row and adjacent, or
// adjacent rows and overlapping columns), or overlap.
bool touchInPlane(const std::vector<PixelRun>& a, const std::vector<PixelRun>& b);

std::size_t pixelCount(const std::vector<PixelRun>& runs);

// Pixels in either run list, sorted and apart as rasterizeSlice returns them.
std::vector<PixelRun> unitePixelRuns(const std::vector<PixelRun>& a, const std::vector<PixelRun>& b);

}  // namespace scansurf
