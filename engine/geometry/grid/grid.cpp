// scansurf: the voxel grid of the classified volume (paper §3.2–3.3): one layer per slice
// plane plus a padding layer on each side (nz = slices + 2), and an in-plane grid whose pixel
// centres 1 and n-2 frame the contours' bounding box, with a background pixel on each side.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "geometry/contours/plane_gaps.h"
#include "geometry/contours/polygon.h"
#include "geometry/contours/validate.h"
#include "geometry/grid/contour_layers.h"
#include "scansurf/grid.h"

namespace scansurf {

namespace {

constexpr int kMaxPixelsPerSide = 16384;

Unexpected badOption(std::string message) { return makeError(Errc::InvalidArgument, std::move(message)); }

struct Axis {
  int n = 0;
  double origin = 0;
  double spacing = 1;
};

// The grid of two in-plane axes over the slice planes (sorted, non-empty), with one
// background layer below and above at the neighbouring spacing (a single plane: singleGap, by
// default the larger pixel spacing).
Grid gridFromAxes(const Axis& ax, const Axis& ay, const std::vector<double>& planes, double singleGap = 0) {
  Grid grid;
  grid.nx = ax.n;
  grid.ny = ay.n;
  grid.originX = ax.origin;
  grid.originY = ay.origin;
  grid.spacingX = ax.spacing;
  grid.spacingY = ay.spacing;
  const std::size_t m = planes.size();
  if (!(singleGap > 0)) singleGap = std::max(ax.spacing, ay.spacing);
  const double below = m > 1 ? planes[1] - planes[0] : singleGap;
  const double above = m > 1 ? planes[m - 1] - planes[m - 2] : singleGap;
  grid.layerZ.reserve(m + 2);
  grid.layerZ.push_back(planes.front() - below);
  grid.layerZ.insert(grid.layerZ.end(), planes.begin(), planes.end());
  grid.layerZ.push_back(planes.back() + above);
  grid.nz = static_cast<int>(grid.layerZ.size());
  return grid;
}

// Square-pixel axis: ceil(extent/s)+1 interior centres centred on [lo, hi], plus a
// background pixel each side.
Result<Axis> axisFromSpacing(double lo, double hi, double s, const char* name) {
  const double extent = hi - lo;
  // The small allowance keeps an extent that is a whole number of pixels from gaining one.
  const double steps = std::max(0.0, std::ceil(extent / s - 1e-9));
  if (!(steps + 3 <= kMaxPixelsPerSide))
    return badOption(std::string("a voxel size of ") + formatNumber(s) + " gives more than " + std::to_string(kMaxPixelsPerSide) +
                     " pixels along " + name);
  Axis axis;
  axis.n = static_cast<int>(steps) + 3;
  axis.spacing = s;
  axis.origin = 0.5 * (lo + hi) - 0.5 * steps * s - s;
  return axis;
}

// The default pixel of a whole file: kDefaultPixels along the longer side of its box.
double defaultSpacing(const ContourSet::Extent& e) {
  return std::max(e.maxX - e.minX, e.maxY - e.minY) / (GridOptions::kDefaultPixels - 3);
}

// The pixels of a lattice (origin, spacing) from the last centre below lo to the first above
// hi, one background pixel each side of [lo, hi], and reaching at least indices first..last;
// nullopt beyond kMaxPixelsPerSide.
std::optional<Axis> latticeWindow(double lo, double hi, double origin, double spacing, double first, double last) {
  first = std::min(first, std::floor((lo - origin) / spacing) - 1);
  last = std::max(last, std::ceil((hi - origin) / spacing) + 1);
  if (!(last - first + 1 <= kMaxPixelsPerSide)) return std::nullopt;
  Axis axis;
  axis.n = static_cast<int>(last - first) + 1;
  axis.spacing = spacing;
  axis.origin = origin + first * spacing;
  return axis;
}

// The part of the whole file's default axis (axisFromSpacing over [fileLo, fileHi]) that holds
// [lo, hi] with a background pixel each side: the same pixel centres whatever was selected.
Result<Axis> axisOnFileLattice(double lo, double hi, double fileLo, double fileHi, double s, const char* name) {
  if (!(s > 0)) return makeError(Errc::InvalidInput, std::string("the file's contours have no extent along ") + name);
  SCANSURF_ASSIGN_OR_RETURN(const Axis file, axisFromSpacing(fileLo, fileHi, s, name));
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const std::optional<Axis> axis = latticeWindow(lo, hi, file.origin, s, kInf, -kInf);
  if (!axis) return badOption(std::string("more than ") + std::to_string(kMaxPixelsPerSide) + " pixels along " + name);
  return *axis;
}

Result<Axis> axisFromCount(double lo, double hi, int n, const char* name) {
  if (n < 4 || n > kMaxPixelsPerSide)
    return badOption(std::string("option grid.n") + name + " must be 4 to " + std::to_string(kMaxPixelsPerSide) +
                     " pixels (got " + std::to_string(n) + ")");
  const double extent = hi - lo;
  if (!(extent > 0))
    return makeError(Errc::InvalidInput, std::string("the contours have no extent along ") + name + ", so n" + name +
                                             " cannot set the pixel size; use a voxel size");
  Axis axis;
  axis.n = n;
  axis.spacing = extent / (n - 3);
  axis.origin = lo - axis.spacing;
  return axis;
}

// The contour planes and the long gaps' cap layers (plane_gaps.h), sorted, one per plane.
std::vector<double> withCapLayers(std::vector<double> planes, const std::vector<double>& caps, double tol) {
  for (double z : caps)
    if (std::none_of(planes.begin(), planes.end(), [&](double p) { return std::abs(p - z) <= tol; })) planes.push_back(z);
  std::sort(planes.begin(), planes.end());
  return planes;
}

// The reference slices that hold contours, at the reference's own z; an error naming the
// first slice that lies on none. Slices between contour planes are not layers: they lie
// between two planes, and what lies there is the between-slice model's (the slab rule, or
// interpolated layers), never background (a 1 mm CT under contours drawn every 2 mm).
Result<std::vector<double>> contourPlanesOn(const ContourSet& contours, const GridReference& ref, double tol,
                                            const std::vector<double>& caps) {
  Grid probe;
  probe.layerZ = ref.sliceZ;
  std::vector<char> used(ref.sliceZ.size(), 0);
  for (const Feature& f : contours.features)
    for (const FeatureSlice& s : f.slices) {
      const int k = layerOfZ(probe, s.z, tol);
      if (k < 0)
        return makeError(Errc::InvalidInput, contours.source + ": feature \"" + f.name + "\", slice z=" + formatNumber(s.z) +
                                                 " is not on a slice of the reference grid");
      used[static_cast<std::size_t>(k)] = 1;
    }
  for (double z : caps) used[static_cast<std::size_t>(nearestLayer(probe, z))] = 1;  // long gaps' cap layers
  std::vector<double> planes;
  for (std::size_t k = 0; k < used.size(); ++k)
    if (used[k]) planes.push_back(ref.sliceZ[k]);
  return planes;
}

// The smallest spacing between the reference slice at z and its neighbours (0: a single slice).
double referenceGapAt(const GridReference& ref, double z) {
  const auto& zs = ref.sliceZ;
  const auto k = static_cast<std::size_t>(std::lower_bound(zs.begin(), zs.end(), z) - zs.begin());
  double gap = 0;
  if (k > 0 && k < zs.size()) gap = zs[k] - zs[k - 1];
  if (k + 1 < zs.size()) gap = gap > 0 ? std::min(gap, zs[k + 1] - zs[k]) : zs[k + 1] - zs[k];
  return gap;
}

// The reference lattice extended by whole pixels so that one background pixel lies beyond
// both the reference and the contours on each side; layers are the reference slices that hold
// contours plus one below and above at the neighbouring spacing.
Result<Grid> gridOnReference(const ContourSet& contours, const GridReference& ref, double tol, const std::vector<double>& caps) {
  if (!(ref.spacingX > 0) || !(ref.spacingY > 0) || !std::isfinite(ref.spacingX) || !std::isfinite(ref.spacingY) ||
      !std::isfinite(ref.originX) || !std::isfinite(ref.originY))
    return badOption("reference grid: spacing must be positive and origin finite");
  if (ref.nx < 1 || ref.ny < 1 || ref.sliceZ.empty()) return badOption("reference grid: no pixels or no slices");
  for (std::size_t k = 0; k < ref.sliceZ.size(); ++k)
    if (!std::isfinite(ref.sliceZ[k]) || (k > 0 && !(ref.sliceZ[k] > ref.sliceZ[k - 1])))
      return badOption("reference grid: slice positions must be finite and strictly increasing");
  SCANSURF_ASSIGN_OR_RETURN(const std::vector<double> planes, contourPlanesOn(contours, ref, tol, caps));
  const Box2 box = boundingBox(contours);
  if (box.empty()) return makeError(Errc::InvalidInput, contours.source + ": no contour points");
  // Pixel indices relative to the reference: the whole reference (-1 .. n) and the contours.
  auto extend = [&](double lo, double hi, double origin, double spacing, int n, const char* name) -> Result<Axis> {
    const std::optional<Axis> axis = latticeWindow(lo, hi, origin, spacing, -1.0, static_cast<double>(n));
    // The data's fault, not the command line's (a CT of 0.001 mm pixels under a body's contours).
    if (!axis)
      return makeError(Errc::InvalidInput, contours.source + ": on the reference lattice (" + formatNumber(spacing) + " " +
                                               contours.units + " pixels) the contours span more than " +
                                               std::to_string(kMaxPixelsPerSide) + " pixels along " + name);
    return *axis;
  };
  SCANSURF_ASSIGN_OR_RETURN(const Axis ax, extend(box.minX, box.maxX, ref.originX, ref.spacingX, ref.nx, "x"));
  SCANSURF_ASSIGN_OR_RETURN(const Axis ay, extend(box.minY, box.maxY, ref.originY, ref.spacingY, ref.ny, "y"));
  return gridFromAxes(ax, ay, planes, planes.size() == 1 ? referenceGapAt(ref, planes.front()) : 0);
}

}  // namespace

namespace {

Result<Grid> layOutGrid(const ContourSet& contours, const GridOptions& options) {
  if (!std::isfinite(options.sliceTolerance) || options.sliceTolerance < 0)
    return badOption("slice tolerance must be finite and not negative");
  const double tol = sliceToleranceOf(contours, options.sliceTolerance);
  if (!std::isfinite(options.gapFactor) || options.gapFactor < 0)
    return badOption("option grid.gapFactor must be 0 (bridge every gap) or more (got " + formatNumber(options.gapFactor) + ")");
  const std::vector<double> caps = capLayers(contours, options.gapFactor, tol);
  if (!std::isfinite(options.voxelSize) || options.voxelSize < 0)
    return badOption("voxel size must be positive and finite, got " + formatNumber(options.voxelSize));
  if (options.nx < 0 || options.ny < 0) return badOption("nx and ny must not be negative");
  const bool haveSize = options.voxelSize > 0;
  const bool haveCounts = options.nx > 0 || options.ny > 0;
  if (haveSize && haveCounts) return badOption("set either a voxel size or nx and ny, not both");
  if (haveCounts && (options.nx == 0 || options.ny == 0)) return badOption("set both nx and ny");
  if (options.reference) {
    if (haveSize || haveCounts) return badOption("set either a reference grid or a voxel size / nx and ny, not both");
    return gridOnReference(contours, *options.reference, tol, caps);
  }
  // The lattice the contours were drawn on, unless the options choose a grid of their own.
  if (contours.reference && !haveSize && !haveCounts) return gridOnReference(contours, *contours.reference, tol, caps);

  const std::vector<double> planes = withCapLayers(contourPlanes(contours, tol), caps, tol);
  if (planes.empty()) return makeError(Errc::InvalidInput, contours.source + ": no slices to build a grid from");

  const Box2 box = boundingBox(contours);
  if (box.empty()) return makeError(Errc::InvalidInput, contours.source + ": no contour points");

  Axis ax, ay;
  if (haveCounts) {
    SCANSURF_ASSIGN_OR_RETURN(ax, axisFromCount(box.minX, box.maxX, options.nx, "x"));
    SCANSURF_ASSIGN_OR_RETURN(ay, axisFromCount(box.minY, box.maxY, options.ny, "y"));
  } else if (!haveSize && contours.fileExtent) {
    SCANSURF_ASSIGN_OR_RETURN(ax, axisOnFileLattice(box.minX, box.maxX, contours.fileExtent->minX, contours.fileExtent->maxX,
                                                    defaultSpacing(*contours.fileExtent), "x"));
    SCANSURF_ASSIGN_OR_RETURN(ay, axisOnFileLattice(box.minY, box.maxY, contours.fileExtent->minY, contours.fileExtent->maxY,
                                                    defaultSpacing(*contours.fileExtent), "y"));
  } else {
    double s = options.voxelSize;
    if (!haveSize) {
      const double longer = std::max(box.width(), box.height());
      if (!(longer > 0))
        return makeError(Errc::InvalidInput, contours.source + ": the contours have no extent; set a voxel size");
      s = longer / (GridOptions::kDefaultPixels - 3);
    }
    SCANSURF_ASSIGN_OR_RETURN(ax, axisFromSpacing(box.minX, box.maxX, s, "x"));
    SCANSURF_ASSIGN_OR_RETURN(ay, axisFromSpacing(box.minY, box.maxY, s, "y"));
  }

  return gridFromAxes(ax, ay, planes);
}

// Surface vertices are float32: at coordinates up to `far` they resolve far * 2^-24. A grid
// whose steps are not at least 16 of those (1/16 of a pixel or layer gap) would give a
// surface of a few distinct positions, or none (contours 1e-200 units wide came out with
// volume 0; at 9.9e6 units with 0.25-unit pixels a PLY held 11 distinct x), so it is refused.
Result<void> checkFloatPrecision(const ContourSet& contours, const Grid& g) {
  const double far =
      std::max({std::abs(g.originX), std::abs(g.originX + (g.nx - 1) * g.spacingX), std::abs(g.originY),
                std::abs(g.originY + (g.ny - 1) * g.spacingY), std::abs(g.layerZ.front()), std::abs(g.layerZ.back())});
  double step = std::min(g.spacingX, g.spacingY);
  for (std::size_t k = 1; k < g.layerZ.size(); ++k) step = std::min(step, g.layerZ[k] - g.layerZ[k - 1]);
  const double resolved = std::max(far * 0x1p-24, 1e-30);  // 1e-30: well within float32's normal range
  if (step >= 16 * resolved) return {};
  return makeError(Errc::InvalidInput, contours.source + ": the grid's steps of " + formatNumber(step) + " " + contours.units +
                                           " at coordinates up to " + formatNumber(far) +
                                           " are finer than float32 surface vertices resolve there (" + formatNumber(resolved) +
                                           "); move the contours nearer the origin or choose coarser pixels");
}

}  // namespace

Result<Grid> makeGrid(const ContourSet& contours, const GridOptions& options) {
  SCANSURF_ASSIGN_OR_RETURN(Grid grid, layOutGrid(contours, options));
  grid.planeTolerance = sliceToleranceOf(contours, options.sliceTolerance);
  SCANSURF_TRY(checkFloatPrecision(contours, grid));
  return grid;
}

int nearestLayer(const Grid& grid, double z) {
  const auto& layers = grid.layerZ;
  if (layers.empty()) return -1;
  const auto it = std::lower_bound(layers.begin(), layers.end(), z);
  if (it == layers.begin()) return 0;
  if (it == layers.end()) return static_cast<int>(layers.size()) - 1;
  return static_cast<int>(it - layers.begin()) - (z - *(it - 1) <= *it - z ? 1 : 0);
}

std::vector<double> contourPlanes(const ContourSet& contours, double tolerance) {
  std::vector<double> zs;
  for (const Feature& f : contours.features)
    for (const FeatureSlice& s : f.slices) zs.push_back(s.z);
  std::sort(zs.begin(), zs.end());
  std::vector<double> planes;
  for (double z : zs)
    if (planes.empty() || z - planes.back() > tolerance) planes.push_back(z);
  return planes;
}

int Grid::layerOfPlane(double z) const { return layerOfZ(*this, z, planeTolerance); }

int layerOfZ(const Grid& grid, double z, double tolerance) {
  const auto& layers = grid.layerZ;
  const auto it = std::lower_bound(layers.begin(), layers.end(), z);
  int best = -1;
  double bestDistance = tolerance;
  // The nearest layer is the one at or just above z, or the one below.
  for (auto candidate : {it, it == layers.begin() ? layers.end() : it - 1}) {
    if (candidate == layers.end()) continue;
    const double d = std::abs(*candidate - z);
    if (d <= bestDistance && (best < 0 || d < bestDistance)) {
      best = static_cast<int>(candidate - layers.begin());
      bestDistance = d;
    }
  }
  return best;
}

std::vector<bool> contourLayers(const Grid& grid, const ContourSet* contours) {
  std::vector<bool> out(static_cast<std::size_t>(grid.nz), false);
  if (contours)
    for (const Feature& f : contours->features)
      for (const FeatureSlice& slice : f.slices)
        if (const int k = grid.layerOfPlane(slice.z); k >= 0) out[static_cast<std::size_t>(k)] = true;
  return out;
}

}  // namespace scansurf
