// Contour-faithful vertices: the "smoothing that conforms to the original contours" that the
// scanline surfacing paper (Lee, Fletcher, Whitaker et al., §3.5) leaves as future work, done
// by placement. A vertex on an in-plane edge between two pixel centres of different labels
// separates them; the contour that made the labels differ crosses that edge, and the
// separating curve of the plane (paper's cross-section) passes through the crossing exactly.
#include "geometry/smoothing/contour_fit.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "geometry/extraction/assembly.h"

namespace scansurf {

Carrier carrierOfKey(std::uint64_t key) {
  const std::uint64_t c[3] = {key & kKeyMask, (key >> kKeyBits) & kKeyMask, (key >> (2 * kKeyBits)) & kKeyMask};
  int residue[3];
  bool thirds = false, quarters = false, halves = false;
  for (int a = 0; a < 3; ++a) {
    residue[a] = static_cast<int>(c[a] % 12);
    thirds |= residue[a] == 4 || residue[a] == 8;
    quarters |= residue[a] == 3 || residue[a] == 9;
    halves |= residue[a] == 6;
  }
  Carrier out;
  const int n = quarters ? 4 : thirds ? 3 : halves ? 2 : 0;
  if (n == 0 || (quarters && thirds)) return out;
  // The barycentre of a chain v0 < v1 < ... has residue 12 * s / n on an axis that the last s
  // corners have stepped along.
  int steps[3];
  for (int a = 0; a < 3; ++a) {
    if ((residue[a] * n) % 12 != 0) return out;
    steps[a] = residue[a] * n / 12;
  }
  out.count = n;
  for (int m = 0; m < n; ++m)
    for (int a = 0; a < 3; ++a) out.corners[m][a] = static_cast<int>(c[a] / 12) + (m >= n - steps[a] ? 1 : 0);
  return out;
}

std::vector<ZKeyRun> runsOfZKey(std::span<const std::uint64_t> keys) {
  std::vector<ZKeyRun> runs;
  for (std::size_t v = 0; v < keys.size();) {
    const std::uint64_t z = (keys[v] >> (2 * kKeyBits)) & kKeyMask;
    std::size_t e = v;
    while (e < keys.size() && ((keys[e] >> (2 * kKeyBits)) & kKeyMask) == z) ++e;
    runs.push_back({z, v, e});
    v = e;
  }
  return runs;
}

namespace {

struct Segment {
  std::uint64_t cell;  // ci + cj * 2^32 over the pixel lattice (u, v) = voxel index units
  int feature;
  double u0, v0, u1, v1;
};

// Crossings of edge a -> b with segment p -> q, as t along a -> b; false when parallel or
// apart.
bool crossing(double au, double av, double bu, double bv, const Segment& s, double& t) {
  const double du = bu - au, dv = bv - av;
  const double eu = s.u1 - s.u0, ev = s.v1 - s.v0;
  const double den = du * ev - dv * eu;
  if (den == 0) return false;
  const double wu = s.u0 - au, wv = s.v0 - av;
  t = (wu * ev - wv * eu) / den;
  const double r = (wu * dv - wv * du) / den;
  return t >= 0 && t <= 1 && r >= 0 && r <= 1;
}

}  // namespace

std::vector<double> fitContourCrossings(const Grid& grid, const ContourSet& contours, std::span<const std::uint64_t> keys,
                                        std::span<const Label> vertexLabels, int threads) {
  std::vector<double> t(keys.size(), -1.0);
  // Each plane's vertices are one run.
  struct Run {
    int layer;
    std::size_t begin, end;
  };
  std::vector<Run> runs;
  for (const ZKeyRun& r : runsOfZKey(keys))
    if (r.z % 12 == 0) runs.push_back({static_cast<int>(r.z / 12), r.begin, r.end});
  // Slices by layer.
  std::vector<std::vector<std::pair<int, const FeatureSlice*>>> slicesOfLayer(static_cast<std::size_t>(grid.nz));
  for (std::size_t f = 0; f < contours.features.size(); ++f)
    for (const FeatureSlice& s : contours.features[f].slices) {
      const int k = grid.layerOfPlane(s.z);
      if (k >= 0) slicesOfLayer[static_cast<std::size_t>(k)].push_back({static_cast<int>(f), &s});
    }

  parallelChunks(runs.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    std::vector<Segment> segments;
    std::vector<std::uint64_t> cells;
    for (std::size_t r = begin; r < end; ++r) {
      const Run& run = runs[r];
      // Each contour segment in pixel units, filed under every cell it touches.
      segments.clear();
      for (const auto& [feature, slice] : slicesOfLayer[static_cast<std::size_t>(run.layer)])
        for (const Contour& c : slice->contours)
          for (std::size_t i = 0; i < c.points.size(); ++i) {
            const Point2& p = c.points[i];
            const Point2& q = c.points[(i + 1) % c.points.size()];
            Segment s{0,
                      feature,
                      (p.x - grid.originX) / grid.spacingX,
                      (p.y - grid.originY) / grid.spacingY,
                      (q.x - grid.originX) / grid.spacingX,
                      (q.y - grid.originY) / grid.spacingY};
            cells.clear();
            appendTouchedCells(s.u0, s.v0, s.u1, s.v1, grid.nx, grid.ny, cells);
            for (const std::uint64_t cell : cells) {
              s.cell = cell;
              segments.push_back(s);
            }
          }
      std::stable_sort(segments.begin(), segments.end(), [](const Segment& a, const Segment& b) { return a.cell < b.cell; });

      for (std::size_t v = run.begin; v < run.end; ++v) {
        const Carrier c = carrierOfKey(keys[v]);
        if (c.count != 2) continue;  // face centroids on the plane are junction points
        const int la = vertexLabels[2 * v], lb = vertexLabels[2 * v + 1];
        const std::uint64_t cell =
            static_cast<std::uint64_t>(c.corners[0][0]) | (static_cast<std::uint64_t>(c.corners[0][1]) << 32);
        const auto range = std::equal_range(segments.begin(), segments.end(), Segment{cell, 0, 0, 0, 0, 0},
                                            [](const Segment& a, const Segment& b) { return a.cell < b.cell; });
        double best = -1;
        for (auto s = range.first; s != range.second; ++s) {
          if (s->feature + 1 != la && s->feature + 1 != lb) continue;
          double tc = 0;
          if (crossing(c.corners[0][0], c.corners[0][1], c.corners[1][0], c.corners[1][1], *s, tc) &&
              (best < 0 || std::abs(tc - 0.5) < std::abs(best - 0.5) ||
               (std::abs(tc - 0.5) == std::abs(best - 0.5) && tc < best)))
            best = tc;
        }
        t[v] = best;
      }
    }
  });
  return t;
}

// Column by column: the segment clipped to the column's closed strip gives its rows. Filing a
// segment under its bounding box instead was O(length^2): a 1001-spike star filed 1.4 GB of
// segments per plane and took 17 s.
void appendTouchedCells(double u0, double v0, double u1, double v1, int nx, int ny, std::vector<std::uint64_t>& cells) {
  constexpr double kSlack = 1e-9;  // pixel units: rounding of the clip never drops a touched cell
  const double du = u1 - u0, dv = v1 - v0;
  const long long ciLo = std::max(0LL, static_cast<long long>(std::ceil(std::min(u0, u1) - kSlack)) - 1);
  const long long ciHi = std::min<long long>(nx - 1, static_cast<long long>(std::floor(std::max(u0, u1) + kSlack)));
  for (long long ci = ciLo; ci <= ciHi; ++ci) {
    double t0 = 0, t1 = 1;
    if (du != 0) {
      t0 = std::clamp((static_cast<double>(ci) - kSlack - u0) / du, 0.0, 1.0);
      t1 = std::clamp((static_cast<double>(ci) + 1 + kSlack - u0) / du, 0.0, 1.0);
    }
    const double va = v0 + t0 * dv, vb = v0 + t1 * dv;
    const long long cjLo = std::max(0LL, static_cast<long long>(std::ceil(std::min(va, vb) - kSlack)) - 1);
    const long long cjHi = std::min<long long>(ny - 1, static_cast<long long>(std::floor(std::max(va, vb) + kSlack)));
    for (long long cj = cjLo; cj <= cjHi; ++cj)
      cells.push_back(static_cast<std::uint64_t>(ci) | (static_cast<std::uint64_t>(cj) << 32));
  }
}

}  // namespace scansurf
