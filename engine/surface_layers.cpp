// scansurf: the bookkeeping of a build in several surface layers (see surface_layers.h).
#include "surface_layers.h"

#include <algorithm>
#include <cstdint>

#include "geometry/remesh/remesh_mesh.h"
#include "geometry/shape/snapping.h"
#include "geometry/simplification/simplify_mesh.h"

namespace scansurf {

ContourSet layerContours(const ContourSet& contours, const OverlapReport& report, int layer) {
  ContourSet subset;
  subset.source = contours.source;
  subset.units = contours.units;
  subset.order = contours.order;
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    const Feature& feature = contours.features[f];
    subset.features.push_back({feature.name, feature.color, {}});
    if (report.features[f].layer == layer) subset.features.back().slices = feature.slices;
  }
  return subset;
}

void appendLayer(Surfaces& into, Surfaces&& layer, const OverlapReport& report, int index) {
  if (index == 0) {
    into = std::move(layer);
    into.mesh.keys.clear();  // per-layer lattice keys do not combine; smoothing is done
    // A feature of another layer may still have triangles here: in the enclosing convention
    // its surface in this layer is the union of the descendants drawn in this layer. Its own
    // surface comes from its own layer.
    for (std::size_t f = 0; f < into.features.size(); ++f)
      if (report.features[f].layer != 0) into.features[f].triangles.clear();
    return;
  }
  const auto offset = static_cast<std::uint32_t>(into.mesh.vertexCount());
  into.mesh.positions.insert(into.mesh.positions.end(), layer.mesh.positions.begin(), layer.mesh.positions.end());
  const std::size_t first = into.mesh.triangles.size();
  into.mesh.triangles.insert(into.mesh.triangles.end(), layer.mesh.triangles.begin(), layer.mesh.triangles.end());
  for (std::size_t i = first; i < into.mesh.triangles.size(); ++i) into.mesh.triangles[i] += offset;
  into.mesh.labels.insert(into.mesh.labels.end(), layer.mesh.labels.begin(), layer.mesh.labels.end());
  accumulate(into.remeshing, layer.remeshing);
  accumulate(into.simplification, layer.simplification);
  accumulate(into.triangleShape, layer.triangleShape);
  for (std::size_t f = 0; f < layer.features.size(); ++f) {
    if (report.features[f].layer != index) continue;
    std::vector<std::uint32_t>& to = into.features[f].triangles;
    to.reserve(to.size() + layer.features[f].triangles.size());
    for (std::uint32_t v : layer.features[f].triangles) to.push_back(v + offset);
  }
}

Grid layerGrid(const Grid& grid, const std::vector<FeatureRegion>& regions, const OverlapReport& report, int layer) {
  if (layer == 0) return grid;
  int i0 = grid.nx, i1 = -1, j0 = grid.ny, j1 = -1, k0 = grid.nz, k1 = -1;
  for (std::size_t f = 0; f < regions.size(); ++f) {
    const FeatureRegion& r = regions[f];
    if (report.features[f].layer != layer || r.maxRow < r.minRow || r.layers.empty()) continue;
    i0 = std::min(i0, r.minColumn), i1 = std::max(i1, r.maxColumn), j0 = std::min(j0, r.minRow), j1 = std::max(j1, r.maxRow);
    k0 = std::min(k0, r.layers.front()), k1 = std::max(k1, r.layers.back());
  }
  if (i1 < 0) return grid;
  i0 = std::max(0, i0 - 1), j0 = std::max(0, j0 - 1), k0 = std::max(0, k0 - 1);
  i1 = std::min(grid.nx - 1, i1 + 1), j1 = std::min(grid.ny - 1, j1 + 1), k1 = std::min(grid.nz - 1, k1 + 1);
  Grid sub = grid;
  sub.nx = i1 - i0 + 1, sub.ny = j1 - j0 + 1, sub.nz = k1 - k0 + 1;
  sub.originX = grid.originX + i0 * grid.spacingX;
  sub.originY = grid.originY + j0 * grid.spacingY;
  sub.layerZ.assign(grid.layerZ.begin() + k0, grid.layerZ.begin() + k1 + 1);
  return sub;
}

}  // namespace scansurf
