// Exact triangle-triangle intersection: orientation predicates with a floating-point filter
// and an exact fallback in expansion arithmetic (Shewchuk 1997: two-sum, two-product via FMA,
// zero-eliminating grow and scale). Non-coplanar triangles meet iff an edge of one meets the
// other (the ends of their common segment lie on edges); coplanar ones are decided in 2D.
#include "geometry/mesh/triangle_intersection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scansurf {
namespace {

// A non-overlapping expansion in increasing magnitude, on the stack: orient3d of 2-term
// differences needs at most 192 terms.
struct Expansion {
  static constexpr int kCapacity = 256;
  double v[kCapacity];
  int n = 0;
  void push(double x) { v[n++] = x; }
};

void twoSum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a, av = x - bv;
  y = (a - av) + (b - bv);
}

// e += b (Shewchuk's Grow-Expansion with zero elimination), in place.
void grow(Expansion& e, double b) {
  double q = b;
  int out = 0;
  for (int i = 0; i < e.n; ++i) {
    double x = 0, y = 0;
    twoSum(q, e.v[i], x, y);
    if (y != 0) e.v[out++] = y;
    q = x;
  }
  e.n = out;
  if (q != 0 || e.n == 0) e.push(q);
}

void add(Expansion& e, const Expansion& f) {
  for (int i = 0; i < f.n; ++i) grow(e, f.v[i]);
}

void addScaled(Expansion& sum, const Expansion& e, double b) {
  for (int i = 0; i < e.n; ++i) {
    const double p = e.v[i] * b;
    grow(sum, std::fma(e.v[i], b, -p));
    grow(sum, p);
  }
}

Expansion mul(const Expansion& e, const Expansion& f) {
  Expansion sum;
  for (int i = 0; i < f.n; ++i) addScaled(sum, e, f.v[i]);
  if (sum.n == 0) sum.push(0);
  return sum;
}

Expansion negate(Expansion e) {
  for (int i = 0; i < e.n; ++i) e.v[i] = -e.v[i];
  return e;
}

Expansion diff(double a, double b) {
  double x = 0, y = 0;
  twoSum(a, -b, x, y);
  Expansion e;
  if (y != 0) e.push(y);
  e.push(x);
  return e;
}

int sign(const Expansion& e) {
  for (int i = e.n - 1; i >= 0; --i)
    if (e.v[i] != 0) return e.v[i] > 0 ? 1 : -1;
  return 0;
}

int signOf(double x) { return (x > 0) - (x < 0); }

constexpr double kFilter = 1e-14;  // generous relative bound on the rounding of the fast path

}  // namespace

int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double det = adx * (bdy * cdz - bdz * cdy) + bdx * (cdy * adz - cdz * ady) + cdx * (ady * bdz - adz * bdy);
  const double permanent = std::abs(adx) * (std::abs(bdy * cdz) + std::abs(bdz * cdy)) +
                           std::abs(bdx) * (std::abs(cdy * adz) + std::abs(cdz * ady)) +
                           std::abs(cdx) * (std::abs(ady * bdz) + std::abs(adz * bdy));
  if (std::abs(det) > kFilter * permanent) return signOf(det);
  if (a == d || b == d || c == d || a == b || a == c || b == c) return 0;  // common in meshes: exact
  // Four points in one axis plane (a contour plane's flat cap, every triangle of a contour
  // plane's cross-section): a column of exact zeros (x - y == 0 only when x == y), so the
  // determinant is exactly 0 without the expansions.
  if ((adx == 0 && bdx == 0 && cdx == 0) || (ady == 0 && bdy == 0 && cdy == 0) || (adz == 0 && bdz == 0 && cdz == 0)) return 0;
  Expansion ad[3], bd[3], cd[3];
  for (int k = 0; k < 3; ++k) ad[k] = diff(a[k], d[k]), bd[k] = diff(b[k], d[k]), cd[k] = diff(c[k], d[k]);
  const auto minor = [](const Expansion& p, const Expansion& q, const Expansion& r, const Expansion& s) {
    Expansion m = mul(p, q);
    add(m, negate(mul(r, s)));
    return m;
  };
  Expansion sum = mul(ad[0], minor(bd[1], cd[2], bd[2], cd[1]));
  add(sum, mul(bd[0], minor(cd[1], ad[2], cd[2], ad[1])));
  add(sum, mul(cd[0], minor(ad[1], bd[2], ad[2], bd[1])));
  return sign(sum);
}

PlaneSide::PlaneSide(const Point3& a, const Point3& b, const Point3& c) : a_(a), b_(b), c_(c) {
  const double e1x = b[0] - a[0], e1y = b[1] - a[1], e1z = b[2] - a[2];
  const double e2x = c[0] - a[0], e2y = c[1] - a[1], e2z = c[2] - a[2];
  minor_ = {e1y * e2z - e1z * e2y, e1z * e2x - e1x * e2z, e1x * e2y - e1y * e2x};
  magnitude_ = {std::abs(e1y * e2z) + std::abs(e1z * e2y), std::abs(e1z * e2x) + std::abs(e1x * e2z),
                std::abs(e1x * e2y) + std::abs(e1y * e2x)};
}

// | a-d ; b-d ; c-d | = (a - d) . ((b - a) x (c - a)): the same cofactor expansion of rounded
// differences as orient3d's, so the same filter bounds its rounding.
int PlaneSide::side(const Point3& d) const {
  const double fx = a_[0] - d[0], fy = a_[1] - d[1], fz = a_[2] - d[2];
  const double det = fx * minor_[0] + fy * minor_[1] + fz * minor_[2];
  const double permanent = std::abs(fx) * magnitude_[0] + std::abs(fy) * magnitude_[1] + std::abs(fz) * magnitude_[2];
  if (std::abs(det) > kFilter * permanent) return signOf(det);
  if (d == a_ || d == b_ || d == c_) return 0;  // common in meshes: exact
  return orient3d(a_, b_, c_, d);
}

int orient2d(const Point3& a, const Point3& b, const Point3& c, int u, int v) {
  const double det = (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
  const double permanent = std::abs((b[u] - a[u]) * (c[v] - a[v])) + std::abs((b[v] - a[v]) * (c[u] - a[u]));
  if (std::abs(det) > kFilter * permanent) return signOf(det);
  Expansion e = mul(diff(b[u], a[u]), diff(c[v], a[v]));
  add(e, negate(mul(diff(b[v], a[v]), diff(c[u], a[u]))));
  return sign(e);
}

namespace {

// A projection plane (u, v) in which the triangle keeps non-zero area; false if degenerate.
bool projectionOf(const std::array<Point3, 3>& t, int& u, int& v) {
  for (int drop = 2; drop >= 0; --drop) {
    u = (drop + 1) % 3;
    v = (drop + 2) % 3;
    if (orient2d(t[0], t[1], t[2], u, v) != 0) return true;
  }
  return false;
}

// Closed segments pq and rs in the plane (u, v) meet.
bool segmentsMeet2d(const Point3& p, const Point3& q, const Point3& r, const Point3& s, int u, int v) {
  const int o1 = orient2d(p, q, r, u, v), o2 = orient2d(p, q, s, u, v);
  const int o3 = orient2d(r, s, p, u, v), o4 = orient2d(r, s, q, u, v);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  const auto within = [&](const Point3& a, const Point3& b, const Point3& c) {  // c on segment ab, given collinear
    return std::min(a[u], b[u]) <= c[u] && c[u] <= std::max(a[u], b[u]) && std::min(a[v], b[v]) <= c[v] &&
           c[v] <= std::max(a[v], b[v]);
  };
  return (o1 == 0 && within(p, q, r)) || (o2 == 0 && within(p, q, s)) || (o3 == 0 && within(r, s, p)) ||
         (o4 == 0 && within(r, s, q));
}

// Point p in the closed triangle t, in the plane (u, v).
bool pointInTriangle2d(const Point3& p, const std::array<Point3, 3>& t, int u, int v) {
  const int s = orient2d(t[0], t[1], t[2], u, v);
  for (int e = 0; e < 3; ++e)
    if (orient2d(t[e], t[(e + 1) % 3], p, u, v) * s < 0) return false;
  return true;
}

// Closed segment pq meets closed triangle t (non-degenerate); s1 and s2 are p's and q's sides
// of t's plane (orient3d(t[0], t[1], t[2], p) and of q).
bool segmentMeetsTriangle(const Point3& p, const Point3& q, const std::array<Point3, 3>& t, int s1, int s2) {
  if (s1 * s2 > 0) return false;
  if (s1 == 0 && s2 == 0) {
    int u = 0, v = 0;
    projectionOf(t, u, v);
    if (pointInTriangle2d(p, t, u, v) || pointInTriangle2d(q, t, u, v)) return true;
    for (int e = 0; e < 3; ++e)
      if (segmentsMeet2d(p, q, t[e], t[(e + 1) % 3], u, v)) return true;
    return false;
  }
  const int a = orient3d(p, q, t[0], t[1]), b = orient3d(p, q, t[1], t[2]), c = orient3d(p, q, t[2], t[0]);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}

// x (x != t[apex]) lies in t's closed angle at vertex `apex`; side is x's side of t's plane.
bool inCone(const Point3& x, int side, const std::array<Point3, 3>& t, int apex) {
  if (side != 0) return false;
  int u = 0, v = 0;
  projectionOf(t, u, v);
  const Point3& o = t[apex];
  const Point3& p = t[(apex + 1) % 3];
  const Point3& q = t[(apex + 2) % 3];
  const int s = orient2d(o, p, q, u, v);
  return orient2d(o, p, x, u, v) * s >= 0 && orient2d(o, x, q, u, v) * s >= 0;
}

// q's vertices' sides of t's plane, orient3d(t[0], t[1], t[2], q[i]), the plane set up once;
// q[shared], a vertex of t too (-1: none), is on the plane without a test.
std::array<int, 3> sidesOf(const std::array<Point3, 3>& t, const std::array<Point3, 3>& q, int shared = -1) {
  const PlaneSide plane(t[0], t[1], t[2]);
  std::array<int, 3> sides{};
  for (int i = 0; i < 3; ++i)
    if (i != shared) sides[i] = plane.side(q[i]);
  return sides;
}

// All the sides but those in `skip` (a bit per vertex) non-zero and equal: then the triangle
// meets the plane at most in the skipped (shared) vertices.
bool strictlyOneSide(const std::array<int, 3>& sides, int skip) {
  int side = 0;
  for (int i = 0; i < 3; ++i) {
    if (skip & (1 << i)) continue;
    if (sides[i] == 0 || (side != 0 && sides[i] != side)) return false;
    side = sides[i];
  }
  return true;
}

bool generalCross(const std::array<Point3, 3>& a, const std::array<Point3, 3>& b) {
  // The usual early exit (Möller 1997): one triangle wholly on one side of the other's plane.
  const std::array<int, 3> sidesB = sidesOf(a, b);  // b's vertices against a's plane
  if (strictlyOneSide(sidesB, 0)) return false;
  const std::array<int, 3> sidesA = sidesOf(b, a);
  if (strictlyOneSide(sidesA, 0)) return false;
  for (int e = 0; e < 3; ++e) {
    const int f = (e + 1) % 3;
    if (segmentMeetsTriangle(a[e], a[f], b, sidesA[e], sidesA[f]) || segmentMeetsTriangle(b[e], b[f], a, sidesB[e], sidesB[f]))
      return true;
  }
  return false;
}

}  // namespace

bool isDegenerate(const std::array<Point3, 3>& t) {
  int u = 0, v = 0;
  return !projectionOf(t, u, v);
}

bool trianglesCross(const std::array<std::uint32_t, 3>& ia, const std::array<Point3, 3>& a,
                    const std::array<std::uint32_t, 3>& ib, const std::array<Point3, 3>& b) {
  int sharedA[3] = {-1, -1, -1};  // for each vertex of a, its position in b or -1
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ia[i] == ib[j]) sharedA[i] = j, ++shared;
  if (shared == 3) return true;  // the same triangle twice
  if (shared == 0) return generalCross(a, b);
  if (shared == 2) {
    int lone = 0;
    while (sharedA[lone] >= 0) ++lone;
    int loneB = 0;
    while (loneB == sharedA[0] || loneB == sharedA[1] || loneB == sharedA[2]) ++loneB;
    const Point3& u = a[(lone + 1) % 3];
    const Point3& v = a[(lone + 2) % 3];
    // Beyond the common edge only if b's third vertex folds onto a's side in a's plane.
    if (orient3d(u, v, a[lone], b[loneB]) != 0) return false;
    int pu = 0, pv = 0;
    projectionOf(a, pu, pv);
    return orient2d(u, v, a[lone], pu, pv) * orient2d(u, v, b[loneB], pu, pv) > 0;
  }
  // One common vertex: the opposite edges must miss the other triangle, and the edges from the
  // common vertex must not run into the other's angle there.
  int va = 0;
  while (sharedA[va] < 0) ++va;
  const int vb = sharedA[va];
  // Only the common vertex on the other's plane: they meet there alone.
  const std::array<int, 3> sidesB = sidesOf(a, b, vb);
  if (strictlyOneSide(sidesB, 1 << vb)) return false;
  const std::array<int, 3> sidesA = sidesOf(b, a, va);
  if (strictlyOneSide(sidesA, 1 << va)) return false;
  const int a1 = (va + 1) % 3, a2 = (va + 2) % 3, b1 = (vb + 1) % 3, b2 = (vb + 2) % 3;
  if (segmentMeetsTriangle(a[a1], a[a2], b, sidesA[a1], sidesA[a2])) return true;
  if (segmentMeetsTriangle(b[b1], b[b2], a, sidesB[b1], sidesB[b2])) return true;
  for (int k = 1; k <= 2; ++k) {
    if (inCone(a[(va + k) % 3], sidesA[(va + k) % 3], b, vb)) return true;
    if (inCone(b[(vb + k) % 3], sidesB[(vb + k) % 3], a, va)) return true;
  }
  return false;
}

}  // namespace scansurf
