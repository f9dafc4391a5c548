#include "support/drawn_shapes.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

namespace scansurf {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kFine = 0.25;  // mm between the points of a true boundary

void appendCurve(std::vector<Point2>& path, double x0, double x1, const std::function<double(double)>& y) {
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(x1 - x0) / kFine)));
  for (int i = 0; i < n; ++i) {
    const double x = x0 + (x1 - x0) * i / n;
    path.push_back({x, y(x)});
  }
}

void appendArc(std::vector<Point2>& path, Point2 centre, double a, double b, double from, double to) {
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(to - from) * std::max(a, b) / kFine)));
  for (int i = 0; i < n; ++i) {
    const double t = from + (to - from) * i / n;
    path.push_back({centre.x + a * std::cos(t), centre.y + b * std::sin(t)});
  }
}

void appendSegment(std::vector<Point2>& path, Point2 p, Point2 q) {
  const int n = std::max(1, static_cast<int>(std::ceil(std::hypot(q.x - p.x, q.y - p.y) / kFine)));
  for (int i = 0; i < n; ++i) path.push_back({p.x + (q.x - p.x) * i / n, p.y + (q.y - p.y) * i / n});
}

// Where y = w(x) meets the ellipse (x/a)^2 + (y/b)^2 = 1 on the side of `sign` (bisection).
double meetEllipse(const std::function<double(double)>& w, double a, double b, double sign) {
  double lo = 0, hi = a;
  for (int i = 0; i < 60; ++i) {
    const double x = 0.5 * (lo + hi), y = w(sign * x);
    ((x / a) * (x / a) + (y / b) * (y / b) < 1 ? lo : hi) = x;
  }
  return sign * lo;
}

// The prostate (above w) and rectum (above-w-limited: below `rectumTop`) of one plane.
std::pair<std::vector<Point2>, std::vector<Point2>> pelvisPaths(double a, double b, const std::function<double(double)>& w,
                                                                const std::function<double(double)>& rectumTop) {
  const double xL = meetEllipse(w, a, b, -1), xR = meetEllipse(w, a, b, 1);
  const double tL = std::atan2(w(xL) / b, xL / a) + (w(xL) < 0 ? 2 * kPi : 0), tR = std::atan2(w(xR) / b, xR / a);
  std::vector<Point2> prostate, rectum;
  appendCurve(prostate, xL, xR, w);
  appendArc(prostate, {0, 0}, a, b, tR, tL);
  appendCurve(rectum, xR, xL, rectumTop);
  appendArc(rectum, {0, 0}, a, b, tL, tR + 2 * kPi);
  return {prostate, rectum};
}

}  // namespace

Contour drawnOutline(const std::vector<Point2>& path, double step, double jitter, ShapeRng& rng) {
  std::vector<double> at{0};  // arc length at each path point
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Point2 p = path[i], q = path[(i + 1) % path.size()];
    at.push_back(at.back() + std::hypot(q.x - p.x, q.y - p.y));
  }
  // A hand's deviation wanders: two slow waves and a little noise, never more than `jitter`.
  const double phase1 = rng.uniform(0, 2 * kPi), phase2 = rng.uniform(0, 2 * kPi);
  Contour c;
  std::size_t seg = 0;
  for (double s = rng.uniform(0, step); s < at.back(); s += step) {
    while (at[seg + 1] < s) ++seg;
    const Point2 p = path[seg], q = path[(seg + 1) % path.size()];
    const double length = at[seg + 1] - at[seg], t = length > 0 ? (s - at[seg]) / length : 0;
    const double tx = length > 0 ? (q.x - p.x) / length : 1, ty = length > 0 ? (q.y - p.y) / length : 0;
    const double offset = jitter * (0.5 * std::sin(2 * kPi * s / 23 + phase1) + 0.3 * std::sin(2 * kPi * s / 7 + phase2) +
                                    0.2 * rng.uniform(-1, 1));
    c.points.push_back({p.x + t * (q.x - p.x) + offset * ty, p.y + t * (q.y - p.y) - offset * tx});
  }
  return c;
}

ContourSet drawnPelvisContours(const DrawnPelvisOptions& o) {
  ContourSet set;
  set.source = "drawn pelvis";
  ShapeRng rng(o.seed);
  Feature body{"BODY", {}, {}}, prostate{"prostate", {}, {}}, rectum{"rectum", {}, {}}, ptv{"PTV", {}, {}};
  const int planes = 14;
  for (int k = 0; k < planes; ++k) {
    const double z = (k - 0.5 * (planes - 1)) * o.sliceSpacing;
    const double f = std::sqrt(1 - (z / 15) * (z / 15)), a = 30 * f, b = 24 * f;
    const auto w = [](double x) { return 3 * std::sin(x / 7); };
    const bool poked = o.pokeDepth > 0 && (k == planes / 2 - 1 || k == planes / 2);
    const auto top = [&](double x) {  // a 6 mm wide poke with 1 mm ramps
      const double d = std::abs(x);
      return w(x) + (poked ? o.pokeDepth * std::clamp(4 - d, 0.0, 1.0) : 0);
    };
    const auto [pPath, rPath] = pelvisPaths(a, b, w, top);
    prostate.slices.push_back({z, {drawnOutline(pPath, 1.0, o.jitter, rng)}});
    rectum.slices.push_back({z, {drawnOutline(rPath, 1.3, o.jitter, rng)}});
    if (o.body) body.slices.push_back({z, {ellipseContour({0, 5}, 110, 80, 256)}});
    if (o.planningVolume) ptv.slices.push_back({z, {ellipseContour({0, 0.45 * b}, 0.6 * a + 5, 0.5 * b + 5, 128)}});
  }
  if (o.body) set.features.push_back(std::move(body));
  set.features.push_back(std::move(prostate));
  set.features.push_back(std::move(rectum));
  if (o.planningVolume) set.features.push_back(std::move(ptv));
  return set;
}

ContourSet drawnSectorsContours(double jitter, std::uint64_t seed) {
  ContourSet set;
  set.source = "drawn sectors";
  ShapeRng rng(seed);
  const char* names[] = {"a", "b", "c"};
  for (int s = 0; s < 3; ++s) {
    Feature f{names[s], {}, {}};
    const double from = kPi / 2 + s * 2 * kPi / 3, to = from + 2 * kPi / 3, r = 20;
    for (int k = 0; k < 8; ++k) {
      std::vector<Point2> path;
      appendSegment(path, {0, 0}, {r * std::cos(from), r * std::sin(from)});
      appendArc(path, {0, 0}, r, r, from, to);
      appendSegment(path, {r * std::cos(to), r * std::sin(to)}, {0, 0});
      f.slices.push_back({(k + 0.5) * 2.0, {drawnOutline(path, 1.0 + 0.15 * s, jitter, rng)}});
    }
    set.features.push_back(std::move(f));
  }
  return set;
}

ContourSet thinOverlapContours(double overlap) {
  ContourSet set;
  set.source = "thin overlap";
  ShapeRng rng(7);
  const double h = overlap / 2;
  const auto square = [&](double x0, double x1) {
    std::vector<Point2> path;
    appendSegment(path, {x0, -20}, {x1, -20});
    appendSegment(path, {x1, -20}, {x1, 20});
    appendSegment(path, {x1, 20}, {x0, 20});
    appendSegment(path, {x0, 20}, {x0, -20});
    return path;
  };
  Feature left{"left", {}, {}}, right{"right", {}, {}};
  for (int k = 0; k < 8; ++k) {
    const double z = (k + 0.5) * 2.0;
    left.slices.push_back({z, {drawnOutline(square(-80, h), 1.0, 0, rng)}});
    right.slices.push_back({z, {drawnOutline(square(-h, 80), 1.0, 0, rng)}});
  }
  set.features = {std::move(left), std::move(right)};
  return set;
}

}  // namespace scansurf
