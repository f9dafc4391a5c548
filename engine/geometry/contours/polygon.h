// scansurf: small planar helpers shared by validation, nesting and coverage.
// Regions follow the even-odd rule of the contour model (paper §3.2, §3.4): a point is inside
// a set of contours when a ray from it crosses their edges an odd number of times.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "scansurf/contours.h"

namespace scansurf {

// Axis-aligned bounding box; empty (min > max) until a point is added.
struct Box2 {
  double minX = 1e300;
  double minY = 1e300;
  double maxX = -1e300;
  double maxY = -1e300;

  bool empty() const { return minX > maxX || minY > maxY; }
  void add(Point2 p);
  void add(const Box2& b);
  bool contains(Point2 p) const { return p.x >= minX && p.x <= maxX && p.y >= minY && p.y <= maxY; }
  // True when b lies within this box (boundaries included).
  bool contains(const Box2& b) const { return b.minX >= minX && b.maxX <= maxX && b.minY >= minY && b.maxY <= maxY; }
  bool overlaps(const Box2& b) const { return b.minX <= maxX && b.maxX >= minX && b.minY <= maxY && b.maxY >= minY; }
  double width() const { return empty() ? 0 : maxX - minX; }
  double height() const { return empty() ? 0 : maxY - minY; }
};

// The box as a contour set's file extent (ContourSet::fileExtent); nullopt when empty.
inline std::optional<ContourSet::Extent> extentOf(const Box2& box) {
  if (box.empty()) return std::nullopt;
  return ContourSet::Extent{box.minX, box.minY, box.maxX, box.maxY};
}

// The file extent of a reader's items (ROIs, objects: anything with `closed` contours of
// `points`), selected or not (ContourSet::fileExtent).
template <typename Items>
std::optional<ContourSet::Extent> closedContoursExtent(const Items& items) {
  Box2 box;
  for (const auto& item : items)
    for (const auto& contour : item.closed)
      for (const Point2& p : contour.points) box.add(p);
  return extentOf(box);
}

Box2 boundingBox(const Contour& contour);
Box2 boundingBox(std::span<const Contour> contours);
// Of every point of every feature; empty when there is none.
Box2 boundingBox(const ContourSet& contours);

// Shoelace area of the closed polygon: positive when counter-clockwise (y up).
double signedArea(const Contour& contour);

// Area of the even-odd region of a slice's contours: where none crosses itself or another, each
// contour adds its absolute area when it lies inside an even number of the others, else
// subtracts it (a hole); otherwise evenOddArea (crossings.h).
double regionArea(std::span<const Contour> contours);

// x where edge a-b crosses the horizontal line at y. Computed from the edge's lower endpoint
// so a shared edge gives the bit-identical value whichever contour and direction it comes from.
double edgeCrossingX(Point2 a, Point2 b, double y);

// Crossing number of a rightward ray from p with the contour. Half-open rule: an edge counts
// when exactly one endpoint is strictly above p.y and p.x is strictly left of the crossing.
// So a point exactly on a vertex or edge is classified consistently: of two contours sharing
// an edge, a point on that edge is inside exactly one of them (the one to its right).
int crossingCount(const Contour& contour, Point2 p);

// Even-odd test of p against the region of a set of contours.
bool insideRegion(std::span<const Contour> contours, Point2 p);

// insideRegion over a region's edges bucketed into rows by y, for many points against one
// region: a point reads only the edges that span its row, with the same half-open rule, so
// the answer is insideRegion's, bit for bit.
class RegionIndex {
 public:
  explicit RegionIndex(std::span<const Contour> contours);
  bool inside(Point2 p) const;

 private:
  int rowOf(double y) const;
  struct Edge {
    Point2 a, b;
  };
  double minY_ = 0, rowsPerUnit_ = 0;
  int rows_ = 1;
  std::vector<std::uint32_t> start_;  // per row, into edges_; rows_ + 1 entries
  std::vector<Edge> edges_;
};

// True when p lies within distance tolerance of an edge of any of the contours.
bool onBoundary(std::span<const Contour> contours, Point2 p, double tolerance);

}  // namespace scansurf
