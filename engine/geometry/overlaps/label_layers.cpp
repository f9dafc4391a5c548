// scansurf: label volumes from each feature's own region, for the files (see label_layers.h).
#include "geometry/overlaps/label_layers.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace scansurf {
namespace {

void paint(LabelVolume& volume, const FeatureRegion& region, Label label) {
  for (std::size_t s = 0; s < region.layers.size(); ++s)
    for (const PixelRun& r : region.runs[s])
      std::fill_n(volume.labels.begin() + static_cast<std::ptrdiff_t>(volume.grid.index(r.begin, r.row, region.layers[s])),
                  r.end - r.begin, label);
}

LabelVolume emptyVolume(const Grid& grid) {
  LabelVolume v;
  v.grid = grid;
  v.labels.assign(grid.voxelCount(), kBackground);
  return v;
}

// Index of the reference lattice's first pixel in the grid, along one axis.
Result<int> latticeOffset(double referenceOrigin, double gridOrigin, double spacing, const char* axis) {
  const double steps = (referenceOrigin - gridOrigin) / spacing;
  const double rounded = std::round(steps);
  if (std::abs(steps - rounded) > 1e-6 || rounded < 0)
    return makeError(Errc::InvalidArgument, std::string("the grid does not lie on the reference lattice along ") + axis);
  return static_cast<int>(rounded);
}

}  // namespace

std::vector<LabelVolume> maskLayerVolumes(const std::vector<FeatureRegion>& regions, const Grid& grid,
                                          const OverlapReport& report) {
  std::vector<LabelVolume> layers;
  for (int l = 0; l < report.maskLayers; ++l) layers.push_back(emptyVolume(grid));
  for (std::size_t f = 0; f < regions.size(); ++f)
    paint(layers[static_cast<std::size_t>(report.features[f].maskLayer)], regions[f], labelOfFeature(static_cast<int>(f)));
  return layers;
}

LabelVolume partitionVolume(const std::vector<FeatureRegion>& regions, const Grid& grid, const std::vector<int>& order) {
  LabelVolume volume = emptyVolume(grid);
  for (auto it = order.rbegin(); it != order.rend(); ++it)  // outermost first: inner ones paint over
    paint(volume, regions[static_cast<std::size_t>(*it)], labelOfFeature(*it));
  return volume;
}

Result<ReferenceCut> cutToReference(const LabelVolume& volume, const GridReference& reference, std::size_t featureCount) {
  const Grid& g = volume.grid;
  if (std::abs(g.spacingX - reference.spacingX) > 1e-9 * reference.spacingX ||
      std::abs(g.spacingY - reference.spacingY) > 1e-9 * reference.spacingY)
    return makeError(Errc::InvalidArgument, "the grid's pixel spacing is not the reference lattice's");
  SCANSURF_ASSIGN_OR_RETURN(const int ox, latticeOffset(reference.originX, g.originX, g.spacingX, "x"));
  SCANSURF_ASSIGN_OR_RETURN(const int oy, latticeOffset(reference.originY, g.originY, g.spacingY, "y"));
  if (ox + reference.nx > g.nx || oy + reference.ny > g.ny)
    return makeError(Errc::InvalidArgument, "the reference lattice reaches beyond the grid");
  ReferenceCut cut;
  Grid& out = cut.volume.grid;
  out.nx = reference.nx, out.ny = reference.ny, out.nz = static_cast<int>(reference.sliceZ.size());
  out.originX = reference.originX, out.originY = reference.originY;
  out.spacingX = g.spacingX, out.spacingY = g.spacingY;
  out.layerZ = reference.sliceZ;
  cut.volume.labels.assign(out.voxelCount(), kBackground);
  // Each reference slice takes the layer whose slab holds it (slices between contour planes
  // take the nearer plane); a feature's voxels are dropped when they lie outside the reference
  // in-plane, or on a layer no reference slice takes.
  std::vector<char> taken(static_cast<std::size_t>(g.nz), 0);
  for (int k = 0; k < out.nz; ++k) {
    const int gk = nearestLayer(g, reference.sliceZ[static_cast<std::size_t>(k)]);
    taken[static_cast<std::size_t>(gk)] = 1;
    for (int j = 0; j < out.ny; ++j)
      for (int i = 0; i < out.nx; ++i) cut.volume.labels[out.index(i, j, k)] = volume.at(i + ox, j + oy, gk);
  }
  cut.dropped.assign(featureCount, 0);
  for (int gk = 0; gk < g.nz; ++gk)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const Label l = volume.at(i, j, gk);
        const bool inside = taken[static_cast<std::size_t>(gk)] && i >= ox && j >= oy && i < ox + out.nx && j < oy + out.ny;
        if (l != kBackground && !inside && l <= featureCount) ++cut.dropped[l - 1];
      }
  return cut;
}

}  // namespace scansurf
