// scansurf tests: every crossing pair of a whole mesh, by the engine's exact triangle test
// (geometry/mesh/triangle_intersection.h) over a uniform grid broad phase.
#include "support/intersections.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scansurf::test {

IntersectionReport findCrossings(std::span<const float> positions, std::span<const std::uint32_t> triangles) {
  IntersectionReport report;
  const std::size_t n = triangles.size() / 3;
  if (n == 0) return report;
  struct Box {
    Point3 lo, hi;
  };
  std::vector<Box> boxes(n);
  std::vector<char> degenerate(n, 0);
  double extent = 0;
  Point3 origin = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  const auto point = [&](std::uint32_t v) { return Point3{positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]}; };
  for (std::size_t t = 0; t < n; ++t) {
    Box b{point(triangles[3 * t]), point(triangles[3 * t])};
    for (int c = 1; c < 3; ++c) {
      const Point3 p = point(triangles[3 * t + c]);
      for (int k = 0; k < 3; ++k) b.lo[k] = std::min(b.lo[k], p[k]), b.hi[k] = std::max(b.hi[k], p[k]);
    }
    for (int k = 0; k < 3; ++k) {
      extent = std::max(extent, b.hi[k] - b.lo[k]);
      origin[k] = std::min(origin[k], b.lo[k]);
    }
    boxes[t] = b;
    if (isDegenerate({point(triangles[3 * t]), point(triangles[3 * t + 1]), point(triangles[3 * t + 2])})) {
      degenerate[t] = 1;
      ++report.degenerate;
    }
  }
  // A uniform grid of cells at least as large as any triangle: each triangle touches at most
  // 8 cells; a pair is tested in the one cell holding the low corner of their box overlap.
  const double cell = std::max(extent, 1e-9) * 1.001;
  const auto cellOf = [&](double x, int k) { return static_cast<std::int64_t>(std::floor((x - origin[k]) / cell)); };
  const auto cellKey = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::uint64_t>(x) | (static_cast<std::uint64_t>(y) << 21) | (static_cast<std::uint64_t>(z) << 42);
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> entries;
  for (std::size_t t = 0; t < n; ++t) {
    if (degenerate[t]) continue;
    const Box& b = boxes[t];
    for (std::int64_t z = cellOf(b.lo[2], 2); z <= cellOf(b.hi[2], 2); ++z)
      for (std::int64_t y = cellOf(b.lo[1], 1); y <= cellOf(b.hi[1], 1); ++y)
        for (std::int64_t x = cellOf(b.lo[0], 0); x <= cellOf(b.hi[0], 0); ++x)
          entries.push_back({cellKey(x, y, z), static_cast<std::uint32_t>(t)});
  }
  std::sort(entries.begin(), entries.end());
  for (std::size_t i = 0; i < entries.size();) {
    std::size_t e = i;
    while (e < entries.size() && entries[e].first == entries[i].first) ++e;
    for (std::size_t p = i; p < e; ++p)
      for (std::size_t q = p + 1; q < e; ++q) {
        const std::uint32_t s = entries[p].second, t = entries[q].second;
        const Box &bs = boxes[s], &bt = boxes[t];
        bool overlap = true;
        Point3 low{};
        for (int k = 0; k < 3; ++k) {
          overlap &= bs.lo[k] <= bt.hi[k] && bt.lo[k] <= bs.hi[k];
          low[k] = std::max(bs.lo[k], bt.lo[k]);
        }
        if (!overlap || cellKey(cellOf(low[0], 0), cellOf(low[1], 1), cellOf(low[2], 2)) != entries[i].first) continue;
        ++report.pairsTested;
        const std::array<std::uint32_t, 3> is = {triangles[3 * s], triangles[3 * s + 1], triangles[3 * s + 2]};
        const std::array<std::uint32_t, 3> it = {triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
        if (trianglesCross(is, {point(is[0]), point(is[1]), point(is[2])}, it, {point(it[0]), point(it[1]), point(it[2])})) {
          ++report.crossings;
          if (report.examples.size() < 8) report.examples.push_back({s, t});
        }
      }
    i = e;
  }
  return report;
}

}  // namespace scansurf::test
