// scansurf: the CPU reference of the interpolation passes (passes/interpolator.cpp): the same
// integer arithmetic, one pixel at a time, for the tests to compare with voxel for voxel.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/interpolation/interpolation_plan.h"
#include "scansurf/grid.h"

namespace scansurf {

struct BatchFields {
  std::vector<std::int32_t> values;      // InterpolationBatch::fieldValues
  std::vector<std::int32_t> layerTable;  // the batch's layer table (buildLayerTable)
};

// Exact squared distance (weights w) from each of n samples to the nearest sample whose
// row distance g is 0: min over q of weightRow * g[q]^2 + weightColumn * (i - q)^2 (Felzenszwalb
// & Huttenlocher 2012, in integers: the parabolas' crossings rounded down, which decides every
// integer sample exactly). v and z hold n and n + 1 ints of scratch.
void lowerEnvelope(const std::int32_t* g, std::size_t stride, int n, std::int32_t weightRow, std::int32_t weightColumn,
                   std::int32_t* v, std::int32_t* z, std::int32_t* out);

// The fixed-point distance of a squared distance: isqrt(min(scale * d2, 2^32 - 1)).
std::int32_t fixedDistance(std::int64_t d2, std::uint32_t scale);

// Distances farther than any on the grid (1/unit pixel): a line with no crossing point.
std::int32_t farDistance(const Grid& grid, const DistanceWeights& weights);

// crossings: planeEdgeCrossings of the volume (edge_crossings.h).
BatchFields distanceFieldsReference(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings,
                                    const InterpolationBatch& batch, const DistanceWeights& weights);

// The batch's output layers (outputLayers of nx * ny words, label | clearance << 16).
std::vector<std::uint32_t> interpolateBatchReference(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings,
                                                     const InterpolationBatch& batch, const DistanceWeights& weights,
                                                     CapShape caps);

}  // namespace scansurf
