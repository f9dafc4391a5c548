// scansurf: a separating-surface vertex's carrier (the lattice simplex it is the barycentre of,
// geometry/smoothing/contour_fit.h) as a region: smoothing and volume restoration keep every vertex
// strictly inside its own, which is what keeps the surfaces from crossing (smoothing.cpp).
#pragma once

#include <algorithm>
#include <cstddef>

#include "geometry/mesh/vec3.h"
#include "geometry/smoothing/contour_fit.h"
#include "scansurf/grid.h"

namespace scansurf {

inline constexpr double kCarrierMargin = 0.02;  // least barycentric weight inside a carrier

// The position of voxel corner c (i, j, k) of the grid (inline: smoothing's inner loops).
inline Vec3 cornerPosition(const Grid& grid, const int c[3]) {
  return {grid.originX + grid.spacingX * c[0], grid.originY + grid.spacingY * c[1], grid.layerZ[static_cast<std::size_t>(c[2])]};
}

// The point of the carrier nearest p in the least-squares sense of its affine span, with its
// barycentric weights clamped to >= kCarrierMargin. Inline: smoothing calls it for every
// vertex of every sweep.
inline Vec3 projectIntoCarrier(const Grid& grid, const Carrier& carrier, const Vec3& p) {
  const int n = carrier.count;
  Vec3 c[4] = {};
  for (int m = 0; m < n; ++m) c[m] = cornerPosition(grid, carrier.corners[m]);
  double e[3][3] = {};  // edge vectors c[m] - c[0]
  for (int m = 1; m < n; ++m)
    for (int a = 0; a < 3; ++a) e[m - 1][a] = c[m][a] - c[0][a];
  const Vec3 d = {p[0] - c[0][0], p[1] - c[0][1], p[2] - c[0][2]};
  double w[4] = {0, 0, 0, 0};
  const auto dot = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  if (n == 2) {
    w[1] = dot(&d[0], e[0]) / dot(e[0], e[0]);
  } else if (n == 3) {
    const double a = dot(e[0], e[0]), b = dot(e[0], e[1]), cc = dot(e[1], e[1]);
    const double r0 = dot(&d[0], e[0]), r1 = dot(&d[0], e[1]);
    const double det = a * cc - b * b;
    w[1] = (r0 * cc - r1 * b) / det;
    w[2] = (a * r1 - b * r0) / det;
  } else {
    // d = e0 w1 + e1 w2 + e2 w3, by Cramer's rule.
    const auto det3 = [](const double* x, const double* y, const double* z) {
      return x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) + x[2] * (y[0] * z[1] - y[1] * z[0]);
    };
    // Columns are e0, e1, e2: det of the matrix whose rows are the transposes is the same.
    const double det = det3(e[0], e[1], e[2]);
    w[1] = det3(&d[0], e[1], e[2]) / det;
    w[2] = det3(e[0], &d[0], e[2]) / det;
    w[3] = det3(e[0], e[1], &d[0]) / det;
  }
  w[0] = 1;
  for (int m = 1; m < n; ++m) w[0] -= w[m];
  double sum = 0;
  for (int m = 0; m < n; ++m) sum += (w[m] = std::max(w[m], kCarrierMargin));
  Vec3 out{0, 0, 0};
  for (int m = 0; m < n; ++m)
    for (int a = 0; a < 3; ++a) out[a] += w[m] / sum * c[m][a];
  return out;
}

}  // namespace scansurf
