// scansurf: vertices between two contour planes that no layer of the grid separates, placed where
// the structure's region, blended across the planes, changes along their grid edge: shape-based
// interpolation (Raya & Udupa 1990) evaluated at the vertices instead of on layers of voxels.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/label_volume.h"

namespace scansurf {

// A structure's signed distance to its outline on one plane (positive inside, even-odd as scan
// conversion fills it), exact within kBlendReach pixels of the outline, or twice the median gap
// between a structure's planes where that is farther, and clamped beyond.
inline constexpr double kBlendReach = 4;

// For each vertex (keys: MultiLabelMesh::keys) on a grid edge from layer k to layer k + 1 where
// one of its two labels (vertexLabels: 2 per vertex; background has no contours) has contours,
// t: the parameter in [0, 1] from the edge's first corner to its second where that label's
// surface crosses the edge (the mean of the two labels' when both have one), -1 for every other
// vertex; interior: whether a label has contours on both layers.
// - Contours on both layers: where the label's blended field is zero. The blend is the
//   interpolation's (geometry/interpolation/interpolation_plan.h): the linear blend of the two
//   planes' fields bent by the monotone cubic Hermite through the label's planes k - 1 and k + 2
//   where it has them and the gaps are alike (core/blend_rules.h), so the surface keeps its
//   slope through a contour plane. Along a slanted edge each plane's field is taken linear between the edge's
//   two columns.
// - Contours on one of them only (the label ends there): where the edge meets the label's round
//   cap over that plane, the interpolation's dome (docs/method.md, "Caps").
// Deterministic for any thread count (0: all).
struct BlendedCrossings {
  std::vector<double> t;
  std::vector<char> interior;
};
// Only gaps of at least a pixel are blended (thinner slices resolve the surface between them
// better than the pixels do, and relaxation keeps thin structures there). A cap reaches only a
// contour plane (of any structure), the grid's padding (layers 0 and nz - 1), or a layer at
// least 3/4 of the structure's usual plane spacing away (a long gap's cap layer): an
// interpolated layer or a reference slice, which carries the nearer plane's labels, lies
// nearer, and the cap spans several layers there (or none).
BlendedCrossings blendedCrossings(const Grid& grid, const ContourSet& contours, std::span<const std::uint64_t> keys,
                                  std::span<const Label> vertexLabels, int threads);

}  // namespace scansurf
