// scansurf: the voxel grid a contour set is scan converted into.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/result.h"

namespace scansurf {

// How the user chooses the in-plane grid. Set voxelSize, or nx and ny, or neither, or a
// reference.
struct GridOptions {
  // In-plane pixel size (input units); square pixels. 0 = not set.
  double voxelSize = 0;
  // Pixels along x and y including the one-pixel background border; the contours' bounding
  // box maps exactly onto the centres of pixels 1 and n-2 (paper §3.3). 0 = not set.
  int nx = 0;
  int ny = 0;
  // When neither is set: square pixels, kDefaultPixels along the longer side.
  static constexpr int kDefaultPixels = 256;
  // Slice z values closer than this (input units) are one plane; 0 = the contour set's own
  // tolerance (sliceToleranceOf: a thousandth of its typical plane spacing).
  double sliceTolerance = 0;
  // When set (and voxelSize, nx, ny are not), the grid is the reference lattice extended by
  // whole pixels: one background pixel beyond the reference and the contours on each side in
  // x and y; its layers are the reference slices that hold contours, one layer below and above
  // them. Every contour slice must lie on a reference slice (within sliceTolerance); reference
  // slices between contour planes belong to the nearer plane (nearestLayer).
  std::optional<GridReference> reference;
  // A feature's consecutive contour planes farther apart than this many times its median plane
  // spacing are not bridged by the slab rule: each side is capped on its own, the grid getting
  // a layer a usual spacing beyond each (docs/input-format.md, "Long gaps"), and a warning
  // names the gap. 0: every gap is bridged. Not negative.
  double gapFactor = 2.0;
};

// A regular in-plane grid stacked over the slice planes.
// Voxel (i, j, k) is centred at (originX + i*spacingX, originY + j*spacingY, layerZ[k]).
// Layers 0 and nz-1, columns 0 and nx-1 and rows 0 and ny-1 are background padding, so
// every surface closes.
struct Grid {
  int nx = 0;
  int ny = 0;
  int nz = 0;
  double originX = 0;
  double originY = 0;
  double spacingX = 1;
  double spacingY = 1;
  std::vector<double> layerZ;  // size nz, strictly increasing
  // Slice z values within this of a layer's z lie on that layer's plane (input units): the
  // run's slice tolerance, set by makeGrid; 0 = exactly. Every stage asks the grid
  // (layerOfPlane) rather than carrying a tolerance of its own.
  double planeTolerance = 0;

  // The layer whose plane holds a slice at z (within planeTolerance), or -1.
  int layerOfPlane(double z) const;

  std::size_t voxelCount() const {
    return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
  }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(nx) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(k));
  }
};

// Builds the grid for a validated contour set. With options.reference, or else the contour
// set's own reference (ContourSet::reference) when the options set no voxel size or counts,
// the grid lies on that lattice. Otherwise: the slice planes (merged within
// options.sliceTolerance) become layers 1..nz-2, padded by one layer on each side at the
// neighbouring slice spacing. Errors: options out of range, or a degenerate extent.
Result<Grid> makeGrid(const ContourSet& contours, const GridOptions& options);

// The contour planes of a set: its slices' distinct z, each the lowest of a group within
// `tolerance` (validation has already moved the slices of one plane onto one z; this groups an
// unvalidated set the same way). Sorted.
std::vector<double> contourPlanes(const ContourSet& contours, double tolerance);

// The layer whose plane is within tolerance of z, or -1 (Grid::layerOfPlane with another
// tolerance).
int layerOfZ(const Grid& grid, double z, double tolerance);

// The layer whose slab holds z: the nearest layer (ties: the lower one), so that a slice of a
// finer image lattice between two contour planes takes the nearer plane's labels (the slab
// rule). The padding layers hold everything beyond the planes' slabs.
int nearestLayer(const Grid& grid, double z);

}  // namespace scansurf
