// scansurf: memory estimate of a build (see footprint.h).
#include "geometry/grid/footprint.h"

#include <algorithm>
#include <cmath>

#include "geometry/contours/polygon.h"
#include "scansurf/label_volume.h"

namespace scansurf {
namespace {

// Pixel boundaries a closed polygon crosses: its Manhattan perimeter in pixels.
double pixelCrossings(const Contour& contour, const Grid& grid) {
  double crossings = 0;
  const std::size_t n = contour.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 a = contour.points[i], b = contour.points[(i + 1) % n];
    crossings += std::abs(b.x - a.x) / grid.spacingX + std::abs(b.y - a.y) / grid.spacingY;
  }
  return crossings;
}

// Crossings of one feature: each slice's contours, and the area that changes from slice to
// slice (the first and last slices' whole area: the caps).
double featureCrossings(const Feature& feature, const Grid& grid) {
  const double pixelArea = grid.spacingX * grid.spacingY;
  double crossings = 0, previousArea = 0;
  for (const FeatureSlice& slice : feature.slices) {
    double area = 0;
    for (const Contour& c : slice.contours) crossings += pixelCrossings(c, grid), area += std::abs(signedArea(c));
    crossings += std::abs(area - previousArea) / pixelArea;
    previousArea = area;
  }
  return crossings + previousArea / pixelArea;
}

// Per estimated vertex, at the peak (smoothing): positions as floats and doubles, lattice key,
// carrier and role, neighbour lists, about two triangles with their label pairs, and each
// triangle again in the two feature surfaces it bounds.
// Set above the measured peaks per vertex, plus the Vulkan driver's own memory (kBaseline);
// docs/limits.md gives the figures.
constexpr double kBytesPerVertex = 300;
constexpr double kBaseline = 128.0 * (1 << 20);
// Vertices per crossing, measured (tests/unit/footprint_test.cpp) on the test shapes at 1 and
// 0.5 mm pixels: 2.1 (torus) to 3.8 (branching); rounded up, so the estimate bounds the mesh.
constexpr double kVerticesPerCrossing = 4;
// The feature surfaces' triangle lists per vertex of a feature's own surface: two triangles of
// three 32-bit indices, with a vector's growth slack.
constexpr double kFeatureBytesPerVertex = 2 * 3 * 4 * 1.5;
// Remeshing's peak per vertex of the remeshed mesh (the network with its reference surface,
// broad phase and batch copies): 390 MB over smoothing's peak for 337 k vertices (phantom,
// --edge-length 0.5 at 1 mm pixels), rounded up.
constexpr double kRemeshBytesPerVertex = 1300;
// The device's batch budget of scan conversion, and per pixel of one batch layer what it holds:
// label image, depth-stencil image and the readback buffer.
constexpr std::uint64_t kBatchBudget = std::uint64_t{64} << 20;
constexpr std::uint64_t kDeviceBytesPerPixel = 16;

}  // namespace

Footprint estimateFootprint(const ContourSet& contours, const Grid& grid, int surfacedLayers, double remeshLength) {
  Footprint f;
  const std::uint64_t plane = static_cast<std::uint64_t>(grid.nx) * static_cast<std::uint64_t>(grid.ny);
  f.labelVoxels = plane * static_cast<std::uint64_t>(grid.nz);
  const double layers = std::max(grid.nz, surfacedLayers);
  const double finer = grid.nz > 0 ? layers / grid.nz : 1.0;
  // Never more than the surfaced grid can hold: a vertex is the barycentre of an edge, face or
  // tetrahedron of the lattice, 7 + 12 + 6 of each cell's own (a contour far finer than its
  // pixels, 1e-200 units wide, gave a perimeter of 1e18 vertices and an "EiB" estimate).
  const double cells = static_cast<double>(plane) * layers;
  // Each feature's own surface, bounded by the grid the same way; the multi-label mesh shares
  // their vertices. The enclosing surfaces copy every triangle into each feature whose region
  // holds one side only: nested features pay for their depth (3 000 nested rings, whose
  // capped mesh the grid bounds to 2 GB, need 116 GiB of feature surfaces).
  double ownVertices = 0;
  for (const Feature& feature : contours.features) {
    const double crossings = featureCrossings(feature, grid) * finer;  // NaN for a pixel area of 0
    ownVertices += std::isfinite(crossings) ? std::min(crossings * kVerticesPerCrossing, 25.0 * cells) : 25.0 * cells;
  }
  f.surfaceVertices = static_cast<std::uint64_t>(std::min({ownVertices, 25.0 * cells, 1e18}));
  const double featureSurfaces = std::min(ownVertices, 1e18) * kFeatureBytesPerVertex;
  // The label volume, once on the host and once as it arrives from the device, plus the mesh.
  // With interpolation, the interpolated volume's clearances besides (2 bytes per voxel).
  const double interpolated = finer > 1 ? static_cast<double>(plane) * layers * sizeof(Label) : 0.0;
  double remeshed = 0;
  if (remeshLength > 0) {
    const double halfVoxel = 0.5 * std::min(grid.spacingX, grid.spacingY);
    const double growth = std::max(1.0, (halfVoxel / remeshLength) * (halfVoxel / remeshLength));
    remeshed = std::min(static_cast<double>(f.surfaceVertices) * growth, 1e18) * kRemeshBytesPerVertex;
  }
  const double host = kBaseline + 2.0 * static_cast<double>(f.labelVoxels) * sizeof(Label) + interpolated +
                      static_cast<double>(f.surfaceVertices) * kBytesPerVertex + featureSurfaces + remeshed;
  f.hostBytes = static_cast<std::uint64_t>(std::min(host, 1.8e19));
  // One batch of scan conversion, the label volume kept on the device until classified and,
  // with interpolation, its volume of 32-bit label | clearance words.
  const double words = finer > 1 ? 4.0 * static_cast<double>(plane) * layers : 0.0;
  const double deviceVolumes = static_cast<double>(f.labelVoxels) * sizeof(Label) + words;
  f.deviceBytes =
      std::max(kBatchBudget, plane * kDeviceBytesPerPixel) + static_cast<std::uint64_t>(std::min(deviceVolumes, 1.8e19));
  return f;
}

}  // namespace scansurf
