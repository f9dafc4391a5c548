#include "support/reference_rasterizer.h"

#include <algorithm>
#include <climits>
#include <cstdint>

#include "geometry/overlaps/raster_rules.h"

namespace scansurf::test {
namespace {

using I64 = std::int64_t;

// Edge function of a -> b at p; with the vertices ordered so the interior is positive, an
// edge is "top" (horizontal, dx < 0) or "left" (dy > 0) in framebuffer coordinates (y down).
I64 edge(const SubpixelPoint& a, const SubpixelPoint& b, I64 px, I64 py) {
  return (px - a.u) * (b.v - a.v) - (py - a.v) * (b.u - a.u);
}
bool topLeft(const SubpixelPoint& a, const SubpixelPoint& b) {
  const I64 dx = b.u - a.u, dy = b.v - a.v;
  return dy > 0 || (dy == 0 && dx < 0);
}
bool inside(I64 e, bool isTopLeft) { return e > 0 || (e == 0 && isTopLeft); }

// Toggles the parity of every pixel whose centre the triangle covers.
void toggleTriangle(SubpixelPoint a, SubpixelPoint b, SubpixelPoint c, int bits, const Grid& grid,
                    std::vector<std::uint8_t>& parity) {
  if (edge(a, b, c.u, c.v) == 0) return;  // degenerate: no fragments
  if (edge(a, b, c.u, c.v) < 0) std::swap(b, c);
  const I64 one = I64{1} << bits, half = one >> 1;
  auto firstCentre = [&](I64 lo) { return std::max<I64>(0, (lo - half + one - 1) >> bits); };
  const I64 i0 = firstCentre(std::min({a.u, b.u, c.u})), j0 = firstCentre(std::min({a.v, b.v, c.v}));
  const I64 i1 = std::min<I64>(grid.nx - 1, (std::max({a.u, b.u, c.u}) - half) >> bits);
  const I64 j1 = std::min<I64>(grid.ny - 1, (std::max({a.v, b.v, c.v}) - half) >> bits);
  const bool tlAB = topLeft(a, b), tlBC = topLeft(b, c), tlCA = topLeft(c, a);
  for (I64 j = j0; j <= j1; ++j) {
    const I64 py = j * one + half;
    for (I64 i = i0; i <= i1; ++i) {
      const I64 px = i * one + half;
      if (inside(edge(a, b, px, py), tlAB) && inside(edge(b, c, px, py), tlBC) && inside(edge(c, a, px, py), tlCA))
        parity[static_cast<std::size_t>(j * grid.nx + i)] ^= 1u;
    }
  }
}

}  // namespace

LabelVolume referenceScanConvert(const ContourSet& contours, const Grid& grid, const std::vector<int>& order, int subPixelBits) {
  LabelVolume volume;
  volume.grid = grid;
  volume.labels.assign(grid.voxelCount(), kBackground);
  std::vector<int> rank(contours.features.size());
  for (std::size_t r = 0; r < order.size(); ++r) rank[static_cast<std::size_t>(order[r])] = static_cast<int>(r);

  const std::size_t layerSize = static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny);
  std::vector<int> bestRank(grid.voxelCount(), INT_MAX);
  std::vector<std::uint8_t> parity(layerSize);
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    for (const FeatureSlice& slice : contours.features[f].slices) {
      const int k = grid.layerOfPlane(slice.z);
      if (k < 0) continue;
      std::fill(parity.begin(), parity.end(), 0);
      for (const Contour& c : slice.contours) {
        std::vector<SubpixelPoint> p;
        for (const Point2& q : c.points) p.push_back(toSubpixel(grid, q.x, q.y, subPixelBits));
        for (std::size_t i = 1; i + 1 < p.size(); ++i) toggleTriangle(p[0], p[i], p[i + 1], subPixelBits, grid, parity);
      }
      for (std::size_t n = 0; n < layerSize; ++n) {
        const std::size_t v = static_cast<std::size_t>(k) * layerSize + n;
        if (parity[n] && rank[f] < bestRank[v]) {
          bestRank[v] = rank[f];
          volume.labels[v] = labelOfFeature(static_cast<int>(f));
        }
      }
    }
  }
  return volume;
}

}  // namespace scansurf::test
