// scansurf: a separating-surface vertex's carrier (the lattice simplex it is the barycentre of,
// geometry/contour_fit.h) as a region: smoothing and volume restoration keep every vertex
// strictly inside its own, which is what keeps the surfaces from crossing (smoothing.cpp).
#pragma once

#include "geometry/contour_fit.h"
#include "geometry/vec3.h"
#include "scansurf/grid.h"

namespace scansurf {

inline constexpr double kCarrierMargin = 0.02;  // least barycentric weight inside a carrier

// The position of voxel corner c (i, j, k) of the grid.
Vec3 cornerPosition(const Grid& grid, const int c[3]);

// The point of the carrier nearest p in the least-squares sense of its affine span, with its
// barycentric weights clamped to >= kCarrierMargin.
Vec3 projectIntoCarrier(const Grid& grid, const Carrier& carrier, const Vec3& p);

}  // namespace scansurf
