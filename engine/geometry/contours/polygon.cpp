// scansurf: planar helpers (see polygon.h). The crossing-number test with the half-open rule
// is the classic scanline fill convention the paper's scan conversion relies on (§3.4).
#include "geometry/contours/polygon.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geometry/contours/crossings.h"

namespace scansurf {

void Box2::add(Point2 p) {
  minX = std::min(minX, p.x);
  minY = std::min(minY, p.y);
  maxX = std::max(maxX, p.x);
  maxY = std::max(maxY, p.y);
}

void Box2::add(const Box2& b) {
  if (b.empty()) return;
  add(Point2{b.minX, b.minY});
  add(Point2{b.maxX, b.maxY});
}

Box2 boundingBox(const Contour& contour) {
  Box2 box;
  for (const Point2& p : contour.points) box.add(p);
  return box;
}

Box2 boundingBox(std::span<const Contour> contours) {
  Box2 box;
  for (const Contour& c : contours) box.add(boundingBox(c));
  return box;
}

Box2 boundingBox(const ContourSet& contours) {
  Box2 box;
  for (const Feature& f : contours.features)
    for (const FeatureSlice& s : f.slices) box.add(boundingBox(s.contours));
  return box;
}

double signedArea(const Contour& contour) {
  const auto& pts = contour.points;
  const std::size_t n = pts.size();
  if (n < 3) return 0;
  // Relative to the first point, to keep precision far from the origin.
  double sum = 0;
  const Point2 o = pts[0];
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double ax = pts[i].x - o.x, ay = pts[i].y - o.y;
    const double bx = pts[i + 1].x - o.x, by = pts[i + 1].y - o.y;
    sum += ax * by - bx * ay;
  }
  return 0.5 * sum;
}

double regionArea(std::span<const Contour> contours) {
  if (!crossingHeights(contours).empty()) return evenOddArea(contours);
  double area = 0;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    if (contours[i].points.empty()) continue;
    const Point2 probe = contours[i].points[0];
    int depth = 0;
    for (std::size_t j = 0; j < contours.size(); ++j)
      if (j != i && (crossingCount(contours[j], probe) & 1)) ++depth;
    const double a = std::abs(signedArea(contours[i]));
    area += (depth % 2 == 0) ? a : -a;
  }
  return area;
}

double edgeCrossingX(Point2 a, Point2 b, double y) {
  if (b.y < a.y || (b.y == a.y && b.x < a.x)) std::swap(a, b);
  if (b.y == a.y) return a.x;
  const double t = (y - a.y) / (b.y - a.y);
  return a.x + t * (b.x - a.x);
}

int crossingCount(const Contour& contour, Point2 p) {
  const auto& pts = contour.points;
  const std::size_t n = pts.size();
  int count = 0;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Point2 a = pts[j];
    const Point2 b = pts[i];
    if ((a.y > p.y) == (b.y > p.y)) continue;
    // Cheap rejection before the division: both endpoints left of p.
    if (a.x <= p.x && b.x <= p.x) continue;
    if (p.x < edgeCrossingX(a, b, p.y)) ++count;
  }
  return count;
}

bool insideRegion(std::span<const Contour> contours, Point2 p) {
  int count = 0;
  for (const Contour& c : contours) count += crossingCount(c, p);
  return (count & 1) != 0;
}

RegionIndex::RegionIndex(std::span<const Contour> contours) {
  std::size_t count = 0;
  double maxY = 0;
  for (const Contour& c : contours)
    for (const Point2& q : c.points) {
      minY_ = count == 0 ? q.y : std::min(minY_, q.y), maxY = count == 0 ? q.y : std::max(maxY, q.y);
      ++count;
    }
  // About two edges a row; rows spanned by long edges hold them all.
  rows_ = static_cast<int>(std::clamp<std::size_t>(count / 2, 1, 4096));
  if (maxY > minY_) rowsPerUnit_ = rows_ / (maxY - minY_);
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(rows_) + 1, 0);
  const auto forEachEdge = [&](auto&& visit) {
    for (const Contour& c : contours)
      for (std::size_t i = 0, n = c.points.size(), j = n - 1; i < n; j = i++) visit(c.points[j], c.points[i]);
  };
  forEachEdge([&](Point2 a, Point2 b) {
    for (int r = rowOf(std::min(a.y, b.y)); r <= rowOf(std::max(a.y, b.y)); ++r) ++counts[static_cast<std::size_t>(r) + 1];
  });
  start_.resize(counts.size());
  std::partial_sum(counts.begin(), counts.end(), start_.begin());
  edges_.resize(start_.back());
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  forEachEdge([&](Point2 a, Point2 b) {
    for (int r = rowOf(std::min(a.y, b.y)); r <= rowOf(std::max(a.y, b.y)); ++r)
      edges_[next[static_cast<std::size_t>(r)]++] = {a, b};
  });
}

// Monotone in y, so an edge spanning p.y lies in every row from its lower end's to its upper's.
int RegionIndex::rowOf(double y) const {
  const double r = (y - minY_) * rowsPerUnit_;
  return r <= 0 ? 0 : r >= rows_ - 1 ? rows_ - 1 : static_cast<int>(r);
}

bool RegionIndex::inside(Point2 p) const {
  const auto r = static_cast<std::size_t>(rowOf(p.y));
  int count = 0;
  for (std::uint32_t e = start_[r]; e < start_[r + 1]; ++e) {
    const Point2 a = edges_[e].a, b = edges_[e].b;
    if ((a.y > p.y) == (b.y > p.y)) continue;
    if (a.x <= p.x && b.x <= p.x) continue;
    if (p.x < edgeCrossingX(a, b, p.y)) ++count;
  }
  return (count & 1) != 0;
}

namespace {

double distanceSquaredToSegment(Point2 p, Point2 a, Point2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = 0;
  if (len2 > 0) t = std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0);
  const double ex = a.x + t * dx - p.x, ey = a.y + t * dy - p.y;
  return ex * ex + ey * ey;
}

}  // namespace

bool onBoundary(std::span<const Contour> contours, Point2 p, double tolerance) {
  const double tol2 = tolerance * tolerance;
  for (const Contour& c : contours) {
    const auto& pts = c.points;
    const std::size_t n = pts.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Point2 a = pts[j], b = pts[i];
      if (p.x < std::min(a.x, b.x) - tolerance || p.x > std::max(a.x, b.x) + tolerance || p.y < std::min(a.y, b.y) - tolerance ||
          p.y > std::max(a.y, b.y) + tolerance)
        continue;
      if (distanceSquaredToSegment(p, a, b) <= tol2) return true;
    }
  }
  return false;
}

}  // namespace scansurf
