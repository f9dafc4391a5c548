// scansurf: exact triangle-triangle intersection, for the "surfaces never cross" checks of
// remeshing and of the tests.
// Orientation signs are exact for any double inputs (a floating-point filter, then Shewchuk's
// expansion arithmetic, "Adaptive precision floating-point arithmetic and fast robust
// geometric predicates", 1997), so touching, coplanar and shared-vertex cases are decided
// exactly rather than by tolerance.
#pragma once

#include <array>
#include <cstdint>

#include "geometry/mesh/vec3.h"

namespace scansurf {

using Point3 = Vec3;  // a point: the geometry's one 3-vector

// Sign (-1, 0, 1) of the determinant | a-d ; b-d ; c-d |: positive when d lies below the plane
// of a, b, c seen counter-clockwise from above (Shewchuk's convention).
int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
// orient3d(a, b, c, d) for many d against one plane: the plane's minors computed once, the same
// exact signs.
class PlaneSide {
 public:
  PlaneSide(const Point3& a, const Point3& b, const Point3& c);
  int side(const Point3& d) const;

 private:
  Point3 a_, b_, c_;
  std::array<double, 3> minor_, magnitude_;  // (b - a) x (c - a), and its terms' absolute sums
};
// Sign of (b-a) x (c-a) in the plane of axes (u, v).
int orient2d(const Point3& a, const Point3& b, const Point3& c, int u, int v);

// Whether two closed triangles intersect anywhere other than where they must: triangles
// given by vertex ids and positions; vertices with the same id are shared. Two triangles
// sharing an edge may meet only on that edge, sharing one vertex only at that vertex.
// Degenerate (collinear) triangles must be filtered out by the caller (isDegenerate).
bool trianglesCross(const std::array<std::uint32_t, 3>& ia, const std::array<Point3, 3>& a,
                    const std::array<std::uint32_t, 3>& ib, const std::array<Point3, 3>& b);
bool isDegenerate(const std::array<Point3, 3>& t);

}  // namespace scansurf
