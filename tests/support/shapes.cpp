// scansurf tests: generated contour sets (see shapes.h).
#include "support/shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scansurf {

namespace {

constexpr double kPi = std::numbers::pi;

int defaultVertices(double radius) { return std::max(16, 4 * static_cast<int>(std::ceil(radius * 8))); }

// Slice planes c ± (k + 0.5) * spacing strictly within distance `reach` of c, ascending.
std::vector<double> symmetricPlanes(double c, double reach, double spacing) {
  std::vector<double> upper;
  for (int k = 0; (k + 0.5) * spacing < reach; ++k) upper.push_back((k + 0.5) * spacing);
  std::vector<double> planes;
  for (auto it = upper.rbegin(); it != upper.rend(); ++it) planes.push_back(c - *it);
  for (double d : upper) planes.push_back(c + d);
  return planes;
}

// The points of a straight run from a to b, excluding b, about `step` apart.
void appendRun(std::vector<Point2>& out, Point2 a, Point2 b, double step) {
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / n;
    out.push_back(Point2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
  }
}

// Arc of the circle from angle a0 to a1 (radians, counter-clockwise), excluding both ends.
void appendArcInterior(std::vector<Point2>& out, Point2 c, double r, double a0, double a1, double step) {
  const int n = std::max(2, static_cast<int>(std::ceil(r * (a1 - a0) / step)));
  for (int i = 1; i < n; ++i) {
    const double a = a0 + (a1 - a0) * i / n;
    out.push_back(Point2{c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
}

// The two halves of a disc split by the vertical line x = centre.x, sharing the identical
// chord points: {left, right}, both counter-clockwise.
std::pair<Contour, Contour> splitDisc(Point2 c, double r, double step) {
  const Point2 bottom{c.x, c.y - r}, top{c.x, c.y + r};
  std::vector<Point2> chord;  // bottom to top, both ends included
  appendRun(chord, bottom, top, step);
  chord.push_back(top);
  Contour left, right;
  appendArcInterior(left.points, c, r, kPi / 2, 3 * kPi / 2, step);       // top -> bottom via the left
  left.points.insert(left.points.end(), chord.begin(), chord.end());      // bottom -> top
  appendArcInterior(right.points, c, r, -kPi / 2, kPi / 2, step);         // bottom -> top via the right
  right.points.insert(right.points.end(), chord.rbegin(), chord.rend());  // top -> bottom
  return {std::move(left), std::move(right)};
}

FeatureSlice sliceOf(double z, std::vector<Contour> contours) {
  FeatureSlice s;
  s.z = z;
  s.contours = std::move(contours);
  return s;
}

}  // namespace

Contour circleContour(Point2 centre, double radius, int vertices) {
  return ellipseContour(centre, radius, radius, vertices > 0 ? vertices : defaultVertices(radius));
}

Contour ellipseContour(Point2 centre, double radiusX, double radiusY, int vertices) {
  Contour c;
  c.points.reserve(vertices);
  for (int i = 0; i < vertices; ++i) {
    const double a = 2 * kPi * i / vertices;
    c.points.push_back(Point2{centre.x + radiusX * std::cos(a), centre.y + radiusY * std::sin(a)});
  }
  return c;
}

ContourSet sphereContours(double radius, double sliceSpacing, Point2 centre, double centreZ) {
  ContourSet set;
  set.source = "sphere";
  Feature f;
  f.name = "sphere";
  f.color = Rgb{200, 80, 80};
  for (double z : symmetricPlanes(centreZ, radius, sliceSpacing)) {
    const double d = z - centreZ;
    f.slices.push_back(sliceOf(z, {circleContour(centre, std::sqrt(radius * radius - d * d))}));
  }
  set.features.push_back(std::move(f));
  return set;
}

ContourSet torusContours(double majorRadius, double tubeRadius, double sliceSpacing) {
  ContourSet set;
  set.source = "torus";
  Feature f;
  f.name = "torus";
  f.color = Rgb{80, 160, 220};
  for (double z : symmetricPlanes(0, tubeRadius, sliceSpacing)) {
    const double w = std::sqrt(tubeRadius * tubeRadius - z * z);
    // The hole as a second contour: even-odd makes it empty.
    f.slices.push_back(sliceOf(z, {circleContour({0, 0}, majorRadius + w), circleContour({0, 0}, majorRadius - w)}));
  }
  set.features.push_back(std::move(f));
  return set;
}

ContourSet tiltedTorusContours(double majorRadius, double tubeRadius, double tiltDegrees, double sliceSpacing) {
  ContourSet set;
  set.source = "tilted_torus";
  Feature f;
  f.name = "torus";
  f.color = Rgb{80, 160, 220};
  const double tilt = tiltDegrees * std::numbers::pi / 180, st = std::sin(tilt), ct = std::cos(tilt);
  constexpr int kSamples = 720;
  // The torus point of angles (u, v), turned by the tilt about x; on the plane z = c the tube
  // angles are the two v with st (R + r cos v) sin u + ct r sin v = c.
  const auto point = [&](double u, double v) {
    const double ring = majorRadius + tubeRadius * std::cos(v);
    const double y = ring * std::sin(u), z = tubeRadius * std::sin(v);
    return Point2{ring * std::cos(u), ct * y - st * z};
  };
  const double reach = majorRadius * st + tubeRadius;
  for (double c : symmetricPlanes(0, reach, sliceSpacing)) {
    std::vector<double> plus(kSamples), minus(kSamples);
    std::vector<char> valid(kSamples);
    for (int k = 0; k < kSamples; ++k) {
      const double u = 2 * std::numbers::pi * k / kSamples;
      const double a = st * tubeRadius * std::sin(u), b = ct * tubeRadius, rhs = c - st * majorRadius * std::sin(u);
      const double q = rhs / std::hypot(a, b);
      valid[k] = std::abs(q) < 1;
      if (!valid[k]) continue;
      const double phase = std::atan2(b, a), spread = std::acos(q);
      plus[k] = phase + spread, minus[k] = phase - spread;
    }
    std::vector<Contour> contours;
    const int firstInvalid = static_cast<int>(std::find(valid.begin(), valid.end(), 0) - valid.begin());
    if (firstInvalid == kSamples) {  // the plane cuts the whole ring: two loops, one inside the other
      Contour outer, inner;
      for (int k = 0; k < kSamples; ++k) {
        const double u = 2 * std::numbers::pi * k / kSamples;
        outer.points.push_back(point(u, plus[k])), inner.points.push_back(point(u, minus[k]));
      }
      contours = {outer, inner};
    } else {  // arcs of the ring: each run of valid u closes through both tube angles
      for (int step = 1; step <= kSamples; ++step) {
        const int k0 = (firstInvalid + step) % kSamples;
        if (!valid[k0] || valid[(k0 + kSamples - 1) % kSamples]) continue;
        std::vector<int> run;
        for (int k = k0; valid[k]; k = (k + 1) % kSamples) run.push_back(k);
        if (run.size() < 3) continue;
        Contour loop;
        for (int k : run) loop.points.push_back(point(2 * std::numbers::pi * k / kSamples, plus[k]));
        for (auto it = run.rbegin(); it != run.rend(); ++it)
          loop.points.push_back(point(2 * std::numbers::pi * *it / kSamples, minus[*it]));
        contours.push_back(loop);
      }
    }
    if (!contours.empty()) f.slices.push_back(sliceOf(c, contours));
  }
  set.features.push_back(std::move(f));
  return set;
}

ContourSet yBranchContours(double trunkRadius, double branchOffset, double branchRadius, double sliceSpacing, int trunkSlices,
                           int branchSlices) {
  ContourSet set;
  set.source = "y_branch";
  Feature f;
  f.name = "vessel";
  f.color = Rgb{220, 40, 40};
  for (int k = 0; k < trunkSlices + branchSlices; ++k) {
    const double z = (k + 0.5) * sliceSpacing;
    if (k < trunkSlices)
      f.slices.push_back(sliceOf(z, {circleContour({0, 0}, trunkRadius)}));
    else
      f.slices.push_back(
          sliceOf(z, {circleContour({-branchOffset, 0}, branchRadius), circleContour({branchOffset, 0}, branchRadius)}));
  }
  set.features.push_back(std::move(f));
  return set;
}

ContourSet nestedSpheresContours(double outerRadius, double innerRadius, double sliceSpacing) {
  ContourSet outer = sphereContours(outerRadius, sliceSpacing);
  ContourSet inner = sphereContours(innerRadius, sliceSpacing);
  ContourSet set;
  set.source = "nested_spheres";
  outer.features[0].name = "outer";
  inner.features[0].name = "inner";
  inner.features[0].color = Rgb{240, 200, 40};
  set.features.push_back(std::move(outer.features[0]));
  set.features.push_back(std::move(inner.features[0]));
  return set;
}

ContourSet thinBarsContours(double width) {
  ContourSet set;
  set.source = "thin bars";
  for (int f = 0; f < 2; ++f) {
    Feature feature;
    feature.name.assign(1, f == 0 ? 'a' : 'b');  // (GCC 12 warns, wrongly, on the const char* assignment)
    for (int k = 0; k < 5; ++k)
      feature.slices.push_back({2.0 * k, {ellipseContour({0, f == 0 ? -1.6 : 1.6}, 10 - k, width / 2, 96)}});
    set.features.push_back(feature);
  }
  return set;
}

ContourSet abuttingContours(double radius, int slices, double sliceSpacing) {
  ContourSet set;
  set.source = "abutting";
  Feature left, right;
  left.name = "left";
  left.color = Rgb{0, 200, 200};
  right.name = "right";
  right.color = Rgb{200, 0, 200};
  const double step = std::max(radius / 16, 2 * kPi * radius / defaultVertices(radius));
  for (int k = 0; k < slices; ++k) {
    const double z = (k + 0.5) * sliceSpacing;
    auto [l, r] = splitDisc({0, 0}, radius, step);
    left.slices.push_back(sliceOf(z, {std::move(l)}));
    right.slices.push_back(sliceOf(z, {std::move(r)}));
  }
  set.features.push_back(std::move(left));
  set.features.push_back(std::move(right));
  return set;
}

// In patient LPS (+y posterior): the organs a little anterior of the middle, the vessel behind
// them and the vertebra at the back.
ContourSet phantomContours(double sliceSpacing) {
  // 100 mm of slices from z = 0; at 2.5 mm the bundled example's 40.
  const int kSlices = static_cast<int>(std::floor(99.0 / sliceSpacing + 1e-9)) + 1;
  const double kSpacing = sliceSpacing;
  constexpr double e = 1e-9;     // z ranges below hold their ends
  constexpr double kStep = 1.0;  // mm between contour points
  ContourSet set;
  set.source = "phantom";
  Feature body{"BODY", Rgb{230, 190, 160}, {}};
  Feature prostate{"prostate", Rgb{0, 200, 200}, {}};
  Feature rectum{"rectum", Rgb{150, 60, 40}, {}};
  Feature target{"target", Rgb{255, 0, 0}, {}};
  Feature vessel{"vessel", Rgb{200, 30, 60}, {}};
  Feature vertebra{"vertebra", Rgb{240, 240, 220}, {}};

  for (int k = 0; k < kSlices; ++k) {
    const double z = k * kSpacing;
    // Skin: an ellipse that swells and narrows gently along z.
    const double scale = 1 + 0.04 * std::sin(z / 15);
    const double a = 60 * scale, b = 40 * scale;
    const double perimeter = kPi * (3 * (a + b) - std::sqrt((3 * a + b) * (a + 3 * b)));
    body.slices.push_back(sliceOf(z, {ellipseContour({0, 0}, a, b, static_cast<int>(std::ceil(perimeter / 1.2)))}));

    // Prostate | rectum: one ellipsoid split by the plane x = -10, sharing the chord exactly.
    if (z >= 22.5 - e && z <= 67.5 + e) {
      const double t = (z - 45) / 27;
      const double r = 14 * std::sqrt(1 - t * t);
      auto [l, rr] = splitDisc({-10, -5}, r, kStep);
      prostate.slices.push_back(sliceOf(z, {std::move(l)}));
      rectum.slices.push_back(sliceOf(z, {std::move(rr)}));
    }
    // Target nested in the prostate.
    if (z >= 37.5 - e && z <= 52.5 + e) target.slices.push_back(sliceOf(z, {circleContour({-18, -5}, 4, 28)}));

    // Vessel: a trunk that splits into two diverging branches (a Y).
    if (z < 50 - e) {
      vessel.slices.push_back(sliceOf(z, {circleContour({30, 15}, 4, 28)}));
    } else {
      const double offset = 3.5 + 0.08 * (z - 50);
      vessel.slices.push_back(sliceOf(z, {circleContour({30 - offset, 15}, 2.5, 20), circleContour({30 + offset, 15}, 2.5, 20)}));
    }

    // Vertebra: a solid disc at its ends, a ring (disc with a hole) in the middle.
    if (z >= 10 - e && z <= 87.5 + e) {
      std::vector<Contour> contours{circleContour({0, 26}, 7, 48)};
      if (z >= 30 - e && z <= 70 + e) contours.push_back(circleContour({0, 26}, 3, 24));
      vertebra.slices.push_back(sliceOf(z, std::move(contours)));
    }
  }
  for (Feature* f : {&body, &prostate, &rectum, &target, &vessel, &vertebra}) set.features.push_back(std::move(*f));
  roundCoordinates(set, 0.01);
  return set;
}

void roundCoordinates(ContourSet& contours, double step) {
  // Dividing by an exact integer gives the double nearest to the decimal (12.34, not
  // 12.340000000000002), so the JSON stays short.
  const double inverse = std::round(1 / step);
  const bool decimal = std::abs(inverse * step - 1) < 1e-12;
  auto round = [&](double v) { return decimal ? std::round(v * inverse) / inverse : std::round(v / step) * step; };
  for (Feature& f : contours.features)
    for (FeatureSlice& s : f.slices)
      for (Contour& c : s.contours) {
        for (Point2& p : c.points) p = Point2{round(p.x), round(p.y)};
        auto same = [](Point2 a, Point2 b) { return a.x == b.x && a.y == b.y; };
        c.points.erase(std::unique(c.points.begin(), c.points.end(), same), c.points.end());
        while (c.points.size() > 1 && same(c.points.front(), c.points.back())) c.points.pop_back();
      }
}

std::uint64_t ShapeRng::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double ShapeRng::uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53; }

Contour randomPolygon(ShapeRng& rng, Point2 centre, double minRadius, double maxRadius, int vertices) {
  Contour c;
  for (int i = 0; i < vertices; ++i) {
    // Jittered angles stay increasing, so the polygon is star-shaped around centre and simple.
    const double a = 2 * kPi * (i + rng.uniform(0.1, 0.9)) / vertices;
    const double r = rng.uniform(minRadius, maxRadius);
    c.points.push_back(Point2{centre.x + r * std::cos(a), centre.y + r * std::sin(a)});
  }
  return c;
}

ContourSet threeSectorsContours() {
  ContourSet set;
  set.source = "three sectors";
  for (int f = 0; f < 3; ++f) {
    Feature feature;
    feature.name = std::string(1, static_cast<char>('a' + f));
    for (int k = 0; k < 6; ++k) {
      Contour c;
      c.points.push_back({0.13, 0.07});  // off the pixel lattice
      const double a0 = 2 * std::numbers::pi * f / 3, a1 = 2 * std::numbers::pi * (f + 1) / 3;
      for (int i = 0; i <= 40; ++i) {
        const double a = a0 + (a1 - a0) * i / 40;
        c.points.push_back({0.13 + 8 * std::cos(a), 0.07 + 8 * std::sin(a)});
      }
      feature.slices.push_back({2.0 * k, {c}});
    }
    set.features.push_back(feature);
  }
  return set;
}

}  // namespace scansurf
