// scansurf: edge meetings of a slice's contours and the even-odd area (crossings.h). Edges are
// binned in a uniform grid about as fine as they are long, so that each edge is tested against
// its few neighbours rather than every edge: near-linear for outlines as drawn.
#include "geometry/contours/crossings.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "geometry/contours/polygon.h"

namespace scansurf {
namespace {

struct Edge {
  Point2 a, b;
  std::uint32_t contour = 0, index = 0, count = 0;  // its contour, its place there, the contour's edges
};

double cross(Point2 o, Point2 a, Point2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// Edges of one contour that share a corner: consecutive, or the last and the first.
bool neighbours(const Edge& e, const Edge& f) {
  if (e.contour != f.contour) return false;
  const std::uint32_t d = e.index > f.index ? e.index - f.index : f.index - e.index;
  return d == 1 || d + 1 == e.count;
}

bool onSegment(Point2 a, Point2 b, Point2 p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

// Where the segments meet (the crossing, or a point of a touch), or none.
std::optional<Point2> meeting(const Edge& e, const Edge& f) {
  const double d1 = cross(e.a, e.b, f.a), d2 = cross(e.a, e.b, f.b);
  const double d3 = cross(f.a, f.b, e.a), d4 = cross(f.a, f.b, e.b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    const double t = d3 / (d3 - d4);
    return Point2{e.a.x + t * (e.b.x - e.a.x), e.a.y + t * (e.b.y - e.a.y)};
  }
  if (d1 == 0 && onSegment(e.a, e.b, f.a)) return f.a;
  if (d2 == 0 && onSegment(e.a, e.b, f.b)) return f.b;
  if (d3 == 0 && onSegment(f.a, f.b, e.a)) return e.a;
  if (d4 == 0 && onSegment(f.a, f.b, e.b)) return e.b;
  return std::nullopt;
}

std::vector<Edge> edgesOf(std::span<const Contour> contours) {
  std::vector<Edge> edges;
  for (std::size_t c = 0; c < contours.size(); ++c) {
    const auto& p = contours[c].points;
    const auto n = static_cast<std::uint32_t>(p.size());
    if (n < 3) continue;
    for (std::uint32_t i = 0; i < n; ++i) edges.push_back({p[i], p[(i + 1) % n], static_cast<std::uint32_t>(c), i, n});
  }
  return edges;
}

// Calls meet(point) for each meeting of two edges that are not neighbours, each pair once;
// stops when meet returns false.
template <typename Meet>
void forEachMeeting(const std::vector<Edge>& edges, Meet&& meet) {
  if (edges.size() < 3) return;
  Box2 box;
  double length = 0;
  for (const Edge& e : edges) {
    box.add(e.a), length += std::hypot(e.b.x - e.a.x, e.b.y - e.a.y);
  }
  // About as long as an edge, but no finer than 2·sqrt(n) cells a side: a long edge across the
  // box then falls in O(n) cells at most.
  const double side = 2 * std::sqrt(static_cast<double>(edges.size())) + 1;
  const double cell =
      std::max({length / static_cast<double>(edges.size()), (box.maxX - box.minX) / side, (box.maxY - box.minY) / side, 1e-300});
  const int nx = static_cast<int>((box.maxX - box.minX) / cell) + 1, ny = static_cast<int>((box.maxY - box.minY) / cell) + 1;
  const auto column = [&](double x) { return std::clamp(static_cast<int>((x - box.minX) / cell), 0, nx - 1); };
  const auto row = [&](double y) { return std::clamp(static_cast<int>((y - box.minY) / cell), 0, ny - 1); };
  // Each edge in every cell its box touches, as (cell, edge) sorted by cell.
  std::vector<std::pair<std::int64_t, std::uint32_t>> binned;
  for (std::uint32_t i = 0; i < edges.size(); ++i) {
    const Edge& e = edges[i];
    for (int y = row(std::min(e.a.y, e.b.y)); y <= row(std::max(e.a.y, e.b.y)); ++y)
      for (int x = column(std::min(e.a.x, e.b.x)); x <= column(std::max(e.a.x, e.b.x)); ++x)
        binned.push_back({static_cast<std::int64_t>(y) * nx + x, i});
  }
  std::sort(binned.begin(), binned.end());
  for (std::size_t begin = 0; begin < binned.size();) {
    std::size_t end = begin;
    while (end < binned.size() && binned[end].first == binned[begin].first) ++end;
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t j = i + 1; j < end; ++j) {
        const Edge& e = edges[binned[i].second];
        const Edge& f = edges[binned[j].second];
        if (neighbours(e, f)) continue;
        const std::optional<Point2> p = meeting(e, f);
        // A pair sharing several cells is counted in the cell that holds its meeting point.
        if (p && static_cast<std::int64_t>(row(p->y)) * nx + column(p->x) == binned[begin].first && !meet(*p)) return;
      }
    begin = end;
  }
}

}  // namespace

std::optional<Point2> firstSelfCrossing(const Contour& contour) {
  std::optional<Point2> found;
  forEachMeeting(edgesOf({&contour, 1}), [&](Point2 p) {
    found = p;
    return false;
  });
  return found;
}

std::vector<double> crossingHeights(std::span<const Contour> contours) {
  std::vector<double> heights;
  forEachMeeting(edgesOf(contours), [&](Point2 p) {
    heights.push_back(p.y);
    return true;
  });
  std::sort(heights.begin(), heights.end());
  return heights;
}

double evenOddArea(std::span<const Contour> contours) {
  const std::vector<Edge> edges = edgesOf(contours);
  std::vector<double> heights = crossingHeights(contours);
  for (const Edge& e : edges) heights.push_back(e.a.y);
  std::sort(heights.begin(), heights.end());
  heights.erase(std::unique(heights.begin(), heights.end()), heights.end());
  double area = 0;
  std::vector<double> xs;
  for (std::size_t k = 0; k + 1 < heights.size(); ++k) {
    const double y = 0.5 * (heights[k] + heights[k + 1]);
    xs.clear();
    for (const Edge& e : edges)
      if ((e.a.y < y) != (e.b.y < y)) xs.push_back(edgeCrossingX(e.a, e.b, y));
    std::sort(xs.begin(), xs.end());
    double width = 0;
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) width += xs[i + 1] - xs[i];
    area += width * (heights[k + 1] - heights[k]);
  }
  return area;
}

}  // namespace scansurf
