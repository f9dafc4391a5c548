// scansurf tests: every crossing pair of a mesh, for the "surfaces never cross" checks, by the
// engine's exact triangle-triangle test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "geometry/mesh/triangle_intersection.h"

namespace scansurf::test {

using scansurf::isDegenerate;
using scansurf::orient2d;
using scansurf::orient3d;
using scansurf::Point3;
using scansurf::trianglesCross;

struct IntersectionReport {
  std::size_t pairsTested = 0;                                    // pairs whose bounding boxes touch
  std::size_t crossings = 0;                                      // pairs for which trianglesCross holds
  std::size_t degenerate = 0;                                     // zero-area triangles (skipped)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> examples;  // first few crossing pairs
};

// Every pair of triangles (3 indices each into xyz positions) with touching bounding boxes,
// tested exactly.
IntersectionReport findCrossings(std::span<const float> positions, std::span<const std::uint32_t> triangles);

}  // namespace scansurf::test
