// scansurf: contour crossings of in-plane grid edges (see edge_crossings.h).
#include "geometry/extraction/edge_crossings.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "geometry/overlaps/overlap_split.h"

namespace scansurf {
namespace {

struct Hit {
  double at;  // position along the grid line, in pixels
  int feature;
};

// Hits of every contour segment of the layer with the grid lines: rows (v = j) and columns (u = i).
void collectHits(const Grid& g, const std::vector<const FeatureSlice*>& slices, const std::vector<int>& features,
                 std::vector<std::vector<Hit>>& rows, std::vector<std::vector<Hit>>& columns) {
  for (std::size_t s = 0; s < slices.size(); ++s)
    for (const Contour& c : slices[s]->contours)
      for (std::size_t i = 0; i < c.points.size(); ++i) {
        const Point2& p = c.points[i];
        const Point2& q = c.points[(i + 1) % c.points.size()];
        const double u0 = (p.x - g.originX) / g.spacingX, v0 = (p.y - g.originY) / g.spacingY;
        const double u1 = (q.x - g.originX) / g.spacingX, v1 = (q.y - g.originY) / g.spacingY;
        if (v0 != v1)
          for (long long j = std::max(0LL, static_cast<long long>(std::ceil(std::min(v0, v1))));
               j <= std::min<long long>(g.ny - 1, static_cast<long long>(std::floor(std::max(v0, v1)))); ++j)
            rows[static_cast<std::size_t>(j)].push_back(
                {u0 + (static_cast<double>(j) - v0) / (v1 - v0) * (u1 - u0), features[s]});
        if (u0 != u1)
          for (long long i2 = std::max(0LL, static_cast<long long>(std::ceil(std::min(u0, u1))));
               i2 <= std::min<long long>(g.nx - 1, static_cast<long long>(std::floor(std::max(u0, u1)))); ++i2)
            columns[static_cast<std::size_t>(i2)].push_back(
                {v0 + (static_cast<double>(i2) - u0) / (u1 - u0) * (v1 - v0), features[s]});
      }
}

// For one grid line of n voxels with labels label(i): the crossing byte of each edge (i, i+1).
template <typename LabelAt, typename Store>
void crossLine(std::vector<Hit>& hits, int n, LabelAt label, Store store) {
  std::sort(hits.begin(), hits.end(),
            [](const Hit& a, const Hit& b) { return a.at < b.at || (a.at == b.at && a.feature < b.feature); });
  std::size_t h = 0;
  for (int i = 0; i + 1 < n; ++i) {
    while (h < hits.size() && hits[h].at < i) ++h;
    const Label a = label(i), b = label(i + 1);
    if (a == b) continue;
    // Prefer a contour of either label's feature; the crossing nearest the edge's middle.
    double best = -1;
    bool bestOwn = false;
    for (std::size_t k = h; k < hits.size() && hits[k].at <= i + 1; ++k) {
      const double t = hits[k].at - i;
      const Label l = labelOfFeature(hits[k].feature);
      const bool own = l == a || l == b;
      if (best < 0 || (own && !bestOwn) || (own == bestOwn && std::abs(t - 0.5) < std::abs(best - 0.5))) best = t, bestOwn = own;
    }
    store(i, best < 0 ? kMidEdge : static_cast<std::uint8_t>(std::clamp(std::lround(best * 256), 0L, 255L)));
  }
}

// Edges between an incidental pair's features cross at the pair's medial line.
void medialEdges(const LabelVolume& volume, int k, const MedialCrossings& medial, std::vector<std::uint16_t>& out) {
  const Grid& g = volume.grid;
  const auto centre = [&](int i, int j) { return Point2{g.originX + i * g.spacingX, g.originY + j * g.spacingY}; };
  const auto byte = [](double t) { return static_cast<std::uint16_t>(std::clamp(std::lround(t * 256), 0L, 255L)); };
  const double z = g.layerZ[static_cast<std::size_t>(k)];
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const Label a = volume.at(i, j, k);
      std::uint16_t& w = out[g.index(i, j, k)];
      if (i + 1 < g.nx && volume.at(i + 1, j, k) != a)
        if (const double t = medial.crossing(a, volume.at(i + 1, j, k), z, centre(i, j), centre(i + 1, j)); t >= 0)
          w = static_cast<std::uint16_t>((w & 0xFF00u) | byte(t));
      if (j + 1 < g.ny && volume.at(i, j + 1, k) != a)
        if (const double t = medial.crossing(a, volume.at(i, j + 1, k), z, centre(i, j), centre(i, j + 1)); t >= 0)
          w = static_cast<std::uint16_t>((w & 0x00FFu) | (byte(t) << 8));
    }
}

}  // namespace

std::vector<std::uint16_t> planeEdgeCrossings(const LabelVolume& volume, const ContourSet& contours, int threads,
                                              const MedialCrossings* medial) {
  const Grid& g = volume.grid;
  std::vector<std::uint16_t> out(volume.labels.size(), static_cast<std::uint16_t>(kMidEdge | (kMidEdge << 8)));
  std::vector<std::vector<const FeatureSlice*>> slices(static_cast<std::size_t>(g.nz));
  std::vector<std::vector<int>> features(static_cast<std::size_t>(g.nz));
  for (std::size_t f = 0; f < contours.features.size(); ++f)
    for (const FeatureSlice& s : contours.features[f].slices) {
      const int k = g.layerOfPlane(s.z);
      if (k < 0) continue;
      slices[static_cast<std::size_t>(k)].push_back(&s);
      features[static_cast<std::size_t>(k)].push_back(static_cast<int>(f));
    }
  parallelChunks(static_cast<std::size_t>(g.nz), threads, [&](int, std::size_t begin, std::size_t end) {
    std::vector<std::vector<Hit>> rows(static_cast<std::size_t>(g.ny)), columns(static_cast<std::size_t>(g.nx));
    for (std::size_t k = begin; k < end; ++k) {
      if (slices[k].empty()) continue;
      for (auto& r : rows) r.clear();
      for (auto& c : columns) c.clear();
      collectHits(g, slices[k], features[k], rows, columns);
      const int layer = static_cast<int>(k);
      for (int j = 0; j < g.ny; ++j)
        crossLine(
            rows[static_cast<std::size_t>(j)], g.nx, [&](int i) { return volume.at(i, j, layer); },
            [&](int i, std::uint8_t t) {
              std::uint16_t& w = out[g.index(i, j, layer)];
              w = static_cast<std::uint16_t>((w & 0xFF00u) | t);
            });
      for (int i = 0; i < g.nx; ++i)
        crossLine(
            columns[static_cast<std::size_t>(i)], g.ny, [&](int j) { return volume.at(i, j, layer); },
            [&](int j, std::uint8_t t) {
              std::uint16_t& w = out[g.index(i, j, layer)];
              w = static_cast<std::uint16_t>((w & 0x00FFu) | (t << 8));
            });
      if (medial && !medial->empty()) medialEdges(volume, layer, *medial, out);
    }
  });
  return out;
}

}  // namespace scansurf
