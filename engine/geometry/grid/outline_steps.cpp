// scansurf: outline steps between contour planes (see outline_steps.h).
#include "geometry/grid/outline_steps.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/contours/polygon.h"

namespace scansurf {
namespace {

struct Outline {
  bool present = false;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0, radius = 0;
};

Outline outlineOf(const FeatureSlice& slice) {
  Outline o;
  for (const Contour& c : slice.contours)
    for (const Point2& p : c.points) {
      if (!o.present) o.x0 = o.x1 = p.x, o.y0 = o.y1 = p.y, o.present = true;
      o.x0 = std::min(o.x0, p.x), o.x1 = std::max(o.x1, p.x), o.y0 = std::min(o.y0, p.y), o.y1 = std::max(o.y1, p.y);
    }
  o.radius = std::sqrt(std::abs(regionArea(slice.contours)) / std::numbers::pi);
  return o;
}

double step(const Outline& a, const Outline& b) {
  return std::max({std::abs(a.x0 - b.x0), std::abs(a.x1 - b.x1), std::abs(a.y0 - b.y0), std::abs(a.y1 - b.y1),
                   std::abs(a.radius - b.radius)});
}

}  // namespace

std::vector<double> outlineSteps(const ContourSet& contours, const Grid& grid) {
  std::vector<double> steps(grid.nz > 1 ? static_cast<std::size_t>(grid.nz - 1) : 0, 0.0);
  const double pixel = std::min(grid.spacingX, grid.spacingY);
  std::vector<Outline> layers(static_cast<std::size_t>(std::max(grid.nz, 0)));
  for (const Feature& f : contours.features) {
    std::fill(layers.begin(), layers.end(), Outline{});
    for (const FeatureSlice& slice : f.slices)
      if (const int k = grid.layerOfPlane(slice.z); k >= 0 && !slice.contours.empty())
        layers[static_cast<std::size_t>(k)] = outlineOf(slice);
    for (std::size_t k = 0; k < steps.size(); ++k)
      if (layers[k].present && layers[k + 1].present) steps[k] = std::max(steps[k], step(layers[k], layers[k + 1]) / pixel);
  }
  return steps;
}

}  // namespace scansurf
