// scansurf: content tiles (see content_tiles.h).
#include "geometry/grid/content_tiles.h"

#include <algorithm>
#include <cmath>

namespace scansurf {
namespace {

ContentTiles emptyTiles(int nx, int ny, int layers) {
  ContentTiles t;
  t.tilesX = (nx + ContentTiles::kTile - 1) / ContentTiles::kTile;
  t.tilesY = (ny + ContentTiles::kTile - 1) / ContentTiles::kTile;
  t.layers = layers;
  t.marks.assign(static_cast<std::size_t>(t.tilesX) * static_cast<std::size_t>(t.tilesY) * static_cast<std::size_t>(layers), 0);
  return t;
}

std::uint8_t* layerMarks(ContentTiles& t, int layer) {
  return t.marks.data() +
         static_cast<std::size_t>(layer) * static_cast<std::size_t>(t.tilesX) * static_cast<std::size_t>(t.tilesY);
}

// Marks the tiles of layer `into` that hold a marked tile of `from`'s layer, widened by `reach`
// tiles.
void markWidened(ContentTiles& t, const std::uint8_t* from, int into, int reach) {
  std::uint8_t* out = layerMarks(t, into);
  for (int ty = 0; ty < t.tilesY; ++ty)
    for (int tx = 0; tx < t.tilesX; ++tx) {
      if (!from[ty * t.tilesX + tx]) continue;
      for (int y = std::max(0, ty - reach); y <= std::min(t.tilesY - 1, ty + reach); ++y)
        for (int x = std::max(0, tx - reach); x <= std::min(t.tilesX - 1, tx + reach); ++x) out[y * t.tilesX + x] = 1;
    }
}

}  // namespace

ContentTiles contentTilesOf(const Grid& grid, const ContourSet& contours) {
  ContentTiles t = emptyTiles(grid.nx, grid.ny, grid.nz);
  const auto pixel = [](double v, double origin, double spacing) { return (v - origin) / spacing; };
  for (const Feature& feature : contours.features)
    for (const FeatureSlice& slice : feature.slices) {
      const int k = grid.layerOfPlane(slice.z);
      if (k < 0) continue;
      std::uint8_t* marks = layerMarks(t, k);
      for (const Contour& c : slice.contours) {
        if (c.points.empty()) continue;
        double u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
        for (const Point2& p : c.points) {
          const double u = pixel(p.x, grid.originX, grid.spacingX), v = pixel(p.y, grid.originY, grid.spacingY);
          u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
        }
        // Pixel centres inside lie in [ceil(u0), floor(u1)]; a pixel more either way for rounding.
        const auto clampTo = [](double x, int n) { return static_cast<int>(std::clamp(x, 0.0, static_cast<double>(n - 1))); };
        const int i0 = clampTo(std::floor(u0) - 1, grid.nx), i1 = clampTo(std::ceil(u1) + 1, grid.nx);
        const int j0 = clampTo(std::floor(v0) - 1, grid.ny), j1 = clampTo(std::ceil(v1) + 1, grid.ny);
        if (!(u1 >= -2 && u0 <= grid.nx + 1 && v1 >= -2 && v0 <= grid.ny + 1)) continue;  // off the grid: draws nothing
        for (int ty = j0 / ContentTiles::kTile; ty <= j1 / ContentTiles::kTile; ++ty)
          for (int tx = i0 / ContentTiles::kTile; tx <= i1 / ContentTiles::kTile; ++tx) marks[ty * t.tilesX + tx] = 1;
      }
    }
  return t;
}

ContentTiles contentTilesOf(const LabelVolume& volume) {
  const Grid& g = volume.grid;
  ContentTiles t = emptyTiles(g.nx, g.ny, g.nz);
  for (int k = 0; k < g.nz; ++k) {
    std::uint8_t* marks = layerMarks(t, k);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (volume.labels[g.index(i, j, k)] != kBackground)
          marks[(j / ContentTiles::kTile) * t.tilesX + i / ContentTiles::kTile] = 1;
  }
  return t;
}

ContentTiles interpolatedContentTiles(const ContentTiles& planes, const std::vector<int>& factors, int reach) {
  int layers = 1;
  for (int n : factors) layers += n;
  ContentTiles t = emptyTiles(planes.tilesX * ContentTiles::kTile, planes.tilesY * ContentTiles::kTile, layers);
  const int widen = (reach + ContentTiles::kTile - 1) / ContentTiles::kTile;
  const std::size_t plane = static_cast<std::size_t>(planes.tilesX) * static_cast<std::size_t>(planes.tilesY);
  int fine = 0;
  for (int k = 0; k < planes.layers; ++k) {
    const std::uint8_t* a = planes.marks.data() + static_cast<std::size_t>(k) * plane;
    markWidened(t, a, fine, 0);
    if (static_cast<std::size_t>(k) >= factors.size()) break;
    const int n = factors[static_cast<std::size_t>(k)];
    if (n > 1) {
      // A structure's window on A or B spans its pixels on their neighbours too.
      for (int j = std::max(0, k - 1); j <= std::min(planes.layers - 1, k + 2); ++j)
        markWidened(t, planes.marks.data() + static_cast<std::size_t>(j) * plane, fine + 1, widen);
      const std::uint8_t* between = layerMarks(t, fine + 1);
      for (int m = 2; m < n; ++m) std::copy(between, between + plane, layerMarks(t, fine + m));
    }
    fine += n;
  }
  return t;
}

}  // namespace scansurf
