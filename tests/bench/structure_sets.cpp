#include "bench/structure_sets.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "support/shapes.h"

namespace scansurf::bench {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Cross-section of a shape on plane z: its contours, or none when it misses the plane.
using Section = std::function<std::vector<Contour>(double z)>;

int verticesFor(double radius, double step) { return std::max(12, static_cast<int>(std::ceil(2 * kPi * radius / step))); }

class Builder {
 public:
  Builder(std::string source, std::vector<double> planes, double step) : planes_(std::move(planes)), step_(step) {
    set_.source = std::move(source);
  }

  void add(const std::string& name, Rgb color, const Section& section) {
    Feature f;
    f.name = name;
    f.color = color;
    for (double z : planes_) {
      std::vector<Contour> contours = section(z);
      if (!contours.empty()) f.slices.push_back({z, std::move(contours)});
    }
    if (!f.slices.empty()) set_.features.push_back(std::move(f));
  }

  // An ellipsoid with semi-axes (a, b, c) centred at (x, y, z0).
  Section ellipsoid(double x, double y, double z0, double a, double b, double c) const {
    return [=, this](double z) -> std::vector<Contour> {
      const double t = (z - z0) / c;
      if (std::abs(t) >= 1) return {};
      const double s = std::sqrt(1 - t * t);
      if (a * s < 0.6 * step_ || b * s < 0.6 * step_) return {};
      return {ellipseContour({x, y}, a * s, b * s, verticesFor(std::max(a, b) * s, step_))};
    };
  }

  // A tube of radius r whose centre moves linearly from (x0, y0) at z0 to (x1, y1) at z1.
  Section tube(double x0, double y0, double z0, double x1, double y1, double z1, double r) const {
    return [=, this](double z) -> std::vector<Contour> {
      if (z < std::min(z0, z1) || z > std::max(z0, z1)) return {};
      const double t = (z - z0) / (z1 - z0);
      return {circleContour({x0 + t * (x1 - x0), y0 + t * (y1 - y0)}, r, verticesFor(r, step_))};
    };
  }

  // A trunk from zTop down to zSplit, then two branches diverging to +-spread at zBottom.
  Section branching(double x, double y, double zTop, double zSplit, double zBottom, double r, double spread) const {
    return [=, this](double z) -> std::vector<Contour> {
      if (z > zTop || z < zBottom) return {};
      if (z >= zSplit) return {circleContour({x, y}, r, verticesFor(r, step_))};
      const double t = (zSplit - z) / (zSplit - zBottom);
      const double off = std::max(0.7 * r, spread * t);
      const double rb = 0.75 * r;
      // While the branches still overlap they are one region: draw their union's outline as
      // two circles would double-count (even-odd), so keep them apart by at least rb.
      const double sep = std::max(off, rb * 1.05);
      return {circleContour({x - sep, y}, rb, verticesFor(rb, step_)), circleContour({x + sep, y}, rb, verticesFor(rb, step_))};
    };
  }

  // A shell: the section of `outer` with the section of `inner` as a hole where it exists.
  static Section shell(const Section& outer, const Section& inner) {
    return [=](double z) {
      std::vector<Contour> c = outer(z);
      if (c.empty()) return c;
      for (Contour& h : inner(z)) c.push_back(std::move(h));
      return c;
    };
  }

  // Two shapes sharing a chord: the section of an ellipsoid split by the plane x = cut; side
  // -1 keeps x < cut, +1 keeps x > cut. Both sides use the identical chord points.
  Section splitEllipsoid(double x, double y, double z0, double a, double b, double c, double cut, int side) const {
    return [=, this](double z) -> std::vector<Contour> {
      const double t = (z - z0) / c;
      if (std::abs(t) >= 1) return {};
      const double s = std::sqrt(1 - t * t), ra = a * s, rb = b * s;
      const double u = (cut - x) / ra;  // chord position in the unit circle
      if (std::abs(u) >= 0.95 || rb < step_) return {};
      const double h = std::sqrt(1 - u * u);
      // Arc from the chord's top end to its bottom end around the chosen side.
      const double aTop = std::atan2(h, u), aBottom = std::atan2(-h, u);
      double start = aTop, end = side < 0 ? aBottom + 2 * kPi : aBottom;
      if (side > 0 && end > start) end -= 2 * kPi;
      const int n = verticesFor(std::max(ra, rb), step_);
      const int arcPoints = std::max(4, static_cast<int>(std::ceil(n * std::abs(end - start) / (2 * kPi))));
      Contour contour;
      for (int i = 0; i <= arcPoints; ++i) {
        const double ang = start + (end - start) * i / arcPoints;
        contour.points.push_back({x + ra * std::cos(ang), y + rb * std::sin(ang)});
      }
      // The chord, bottom to top, through shared interior points.
      const int chordPoints = std::max(1, static_cast<int>(2 * rb * h / step_));
      for (int i = 1; i < chordPoints; ++i) contour.points.push_back({cut, y - rb * h + 2 * rb * h * i / chordPoints});
      return {contour};
    };
  }

  ContourSet take() {
    roundCoordinates(set_, 0.01);
    return std::move(set_);
  }

 private:
  ContourSet set_;
  std::vector<double> planes_;
  double step_;
};

std::vector<double> planes(int count, double spacing, double z0 = 0) {
  std::vector<double> p;
  for (int k = 0; k < count; ++k) p.push_back(z0 + k * spacing);
  return p;
}

Rgb paletteColor(int i) {
  static const Rgb kColors[] = {{230, 25, 75},  {60, 180, 75},   {255, 225, 25}, {0, 130, 200},  {245, 130, 48},
                                {145, 30, 180}, {70, 240, 240},  {240, 50, 230}, {210, 245, 60}, {250, 190, 212},
                                {0, 128, 128},  {220, 190, 255}, {170, 110, 40}, {128, 0, 0},    {170, 255, 195}};
  return kColors[static_cast<std::size_t>(i) % std::size(kColors)];
}

ContourSet pelvis() {
  // 200 slices at 2 mm, z from 0 (feet) to 398 (head); body ~ 480 x 330 mm.
  Builder b("pelvis", planes(200, 2.0), 1.5);
  const Section body = [&](double z) -> std::vector<Contour> {
    const double s = 1 + 0.05 * std::sin(z / 60);
    return {ellipseContour({0, 0}, 235 * s, 160 * s, 700)};
  };
  b.add("BODY", {255, 220, 180}, body);
  b.add("Bladder", {255, 255, 0}, b.ellipsoid(0, 45, 200, 45, 35, 40));
  b.add("Prostate", {0, 200, 200}, b.splitEllipsoid(0, -15, 150, 24, 22, 30, 10, -1));
  b.add("Rectum", {150, 75, 0}, b.splitEllipsoid(0, -15, 150, 24, 22, 30, 10, +1));
  b.add("Sigmoid", {120, 60, 0}, b.tube(30, -55, 110, 20, -60, 300, 16));
  b.add("CTV", {255, 0, 0}, b.ellipsoid(-5, -15, 150, 12, 12, 18));
  b.add("GTV", {255, 0, 255}, b.ellipsoid(-5, -15, 150, 6, 6, 8));
  b.add("PTV", {255, 128, 0}, b.ellipsoid(0, -15, 150, 32, 30, 38));
  b.add("SeminalVes_L", {0, 100, 255}, b.ellipsoid(-20, -35, 190, 14, 6, 10));
  b.add("SeminalVes_R", {0, 100, 255}, b.ellipsoid(20, -35, 190, 14, 6, 10));
  b.add("FemoralHead_L", {230, 230, 200}, b.ellipsoid(-95, 0, 170, 25, 25, 25));
  b.add("FemoralHead_R", {230, 230, 200}, b.ellipsoid(95, 0, 170, 25, 25, 25));
  b.add("Femur_L", {220, 220, 190}, Builder::shell(b.tube(-110, 0, 0, -98, 0, 150, 16), b.tube(-110, 0, 0, -98, 0, 150, 8)));
  b.add("Femur_R", {220, 220, 190}, Builder::shell(b.tube(110, 0, 0, 98, 0, 150, 16), b.tube(110, 0, 0, 98, 0, 150, 8)));
  b.add("Ilium_L", {240, 240, 210},
        Builder::shell(b.ellipsoid(-120, -20, 280, 45, 25, 80), b.ellipsoid(-120, -20, 280, 35, 15, 70)));
  b.add("Ilium_R", {240, 240, 210},
        Builder::shell(b.ellipsoid(120, -20, 280, 45, 25, 80), b.ellipsoid(120, -20, 280, 35, 15, 70)));
  b.add("Sacrum", {200, 200, 160}, b.ellipsoid(0, -95, 290, 40, 18, 60));
  b.add("Coccyx", {190, 190, 150}, b.tube(0, -95, 200, 0, -100, 232, 6));
  b.add("PubicSymphysis", {210, 210, 180}, b.ellipsoid(0, 85, 175, 30, 10, 18));
  b.add("PenileBulb", {180, 0, 90}, b.ellipsoid(0, 10, 105, 10, 8, 10));
  b.add("Aorta_Iliacs", {200, 0, 0}, b.branching(-15, -60, 398, 330, 230, 10, 60));
  b.add("IVC_Iliacs", {0, 0, 200}, b.branching(20, -62, 398, 320, 230, 12, 55));
  b.add("SpinalCanal", {255, 255, 128}, b.tube(0, -120, 300, 0, -125, 398, 8));
  b.add("Bowel", {255, 200, 150}, [&](double z) -> std::vector<Contour> {
    if (z < 240 || z > 380) return {};
    std::vector<Contour> loops;
    for (int i = 0; i < 5; ++i) {
      const double a = i * 2 * kPi / 5 + z / 40;
      loops.push_back(circleContour({70 * std::cos(a), 40 + 30 * std::sin(a)}, 12, 52));
    }
    return loops;
  });
  for (int i = 0; i < 6; ++i) {
    const double x = (i % 2 ? 1 : -1) * (45 + 8 * i), y = -30 + 6 * i, z = 200 + 14 * i;
    b.add("LymphNode_" + std::to_string(i + 1), paletteColor(i), b.ellipsoid(x, y, z, 6 + i % 3, 5, 7));
  }
  return b.take();
}

ContourSet headNeck() {
  // 160 slices at 2.5 mm (400 mm), head and neck ~ 200 x 240 mm.
  Builder b("head-neck", planes(160, 2.5), 1.0);
  b.add("BODY", {255, 220, 180}, [&](double z) -> std::vector<Contour> {
    const double s = z > 250 ? 1.0 : 0.7 + 0.3 * z / 250;  // neck narrower than head
    return {ellipseContour({0, 0}, 95 * s, 115 * s, 600)};
  });
  b.add("Brain", {255, 190, 190}, b.ellipsoid(0, 0, 320, 70, 90, 60));
  b.add("Brainstem", {200, 100, 100}, b.tube(0, -15, 230, 0, -10, 285, 12));
  b.add("SpinalCord", {255, 255, 0}, b.tube(0, -40, 0, 0, -25, 232, 6));
  b.add("SpinalCanal", {255, 255, 150}, Builder::shell(b.tube(0, -40, 0, 0, -25, 232, 10), b.tube(0, -40, 0, 0, -25, 232, 7)));
  for (int side : {-1, 1}) {
    const std::string s = side < 0 ? "_L" : "_R";
    b.add("Eye" + s, {255, 255, 255}, b.ellipsoid(side * 32, 70, 290, 12, 12, 12));
    b.add("Lens" + s, {0, 255, 255}, b.ellipsoid(side * 32, 79, 290, 4, 2.5, 3));
    b.add("OpticNerve" + s, {255, 200, 0}, b.tube(side * 30, 58, 290, side * 8, 25, 287, 2.2));
    b.add("Cochlea" + s, {255, 0, 255}, b.ellipsoid(side * 45, -5, 262, 3, 3, 3));
    b.add("Parotid" + s, {0, 200, 0}, b.ellipsoid(side * 55, -5, 215, 15, 22, 25));
    b.add("Submandibular" + s, {0, 150, 0}, b.ellipsoid(side * 38, 30, 170, 10, 12, 12));
    b.add("Thyroid" + s, {180, 80, 0}, b.ellipsoid(side * 14, 20, 85, 8, 10, 20));
  }
  b.add("Chiasm", {255, 150, 0}, b.ellipsoid(0, 25, 287, 10, 4, 3));
  b.add("Pituitary", {255, 100, 200}, b.ellipsoid(0, 15, 278, 5, 5, 4));
  b.add("Mandible", {230, 230, 200}, [&](double z) -> std::vector<Contour> {
    if (z < 160 || z > 205) return {};
    std::vector<Contour> c{ellipseContour({0, 30}, 50, 55, 300)};
    c.push_back(ellipseContour({0, 22}, 42, 47, 280));  // hollow: a U-like shell
    return c;
  });
  b.add("OralCavity", {255, 100, 100}, b.ellipsoid(0, 35, 190, 30, 25, 18));
  b.add("Larynx", {150, 150, 255}, Builder::shell(b.tube(0, 25, 100, 0, 28, 150, 18), b.tube(0, 25, 100, 0, 28, 150, 10)));
  b.add("Trachea", {100, 100, 255}, Builder::shell(b.tube(0, 20, 0, 0, 25, 100, 10), b.tube(0, 20, 0, 0, 25, 100, 7)));
  b.add("Esophagus", {200, 150, 100}, b.tube(0, -5, 0, 0, 0, 140, 7));
  b.add("PTV70", {255, 0, 0}, b.ellipsoid(-30, 20, 150, 30, 30, 40));
  b.add("CTV70", {255, 128, 0}, b.ellipsoid(-30, 20, 150, 22, 22, 32));
  b.add("GTV", {255, 0, 255}, b.ellipsoid(-30, 20, 150, 12, 12, 15));
  b.add("PTV56", {255, 200, 0}, b.ellipsoid(30, 10, 120, 25, 30, 60));
  for (int v = 0; v < 7; ++v) {
    const double z = 40 + 28 * v;
    b.add("Vertebra_C" + std::to_string(7 - v), {230, 230, 210},
          Builder::shell(b.ellipsoid(0, -40 + 2 * v, z, 18, 16, 11), b.ellipsoid(0, -40 + 2 * v, z, 8, 8, 12)));
  }
  ShapeRng rng(2026);
  for (int i = 0; i < 44; ++i) {
    const double side = i % 2 ? 1 : -1;
    const double x = side * rng.uniform(25, 70), y = rng.uniform(-30, 40), z = rng.uniform(30, 220), r = rng.uniform(2, 7);
    b.add("LymphNode_" + std::to_string(i + 1), paletteColor(i), b.ellipsoid(x, y, z, r, r * 0.8, r));
  }
  return b.take();
}

ContourSet emCells() {
  // 300 serial sections at 0.05 um; a 40 x 40 um field; units um.
  Builder b("em-cells", planes(300, 0.05), 0.04);
  ShapeRng rng(42);
  for (int i = 0; i < 2000; ++i) {
    // A process that branches once (a neurite, a tubule): trunk, then two diverging branches;
    // a third of them thick and short like cell bodies with two processes.
    const double x = rng.uniform(-19, 19), y = rng.uniform(-19, 19), z = rng.uniform(1.5, 13.5);
    const bool body = i % 3 == 0;
    const double r = body ? rng.uniform(0.3, 0.5) : rng.uniform(0.12, 0.25);
    const double up = body ? rng.uniform(0.5, 1.0) : rng.uniform(1, 3), down = body ? rng.uniform(0.5, 1.0) : rng.uniform(1, 3);
    b.add("cell_" + std::to_string(i + 1), paletteColor(i),
          b.branching(x, y, std::min(14.95, z + up), z, std::max(0.0, z - down), r, rng.uniform(0.6, 1.2)));
  }
  ContourSet set = b.take();
  set.units = "um";
  return set;
}

}  // namespace

std::vector<std::string> structureSetNames() { return {"pelvis", "head-neck", "em-cells"}; }

StructureSetSpec makeStructureSet(const std::string& name) {
  if (name == "pelvis") return {name, pelvis()};
  if (name == "head-neck") return {name, headNeck()};
  if (name == "em-cells") return {name, emCells()};
  return {name, {}};
}

}  // namespace scansurf::bench
