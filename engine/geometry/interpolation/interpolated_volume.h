// scansurf: a label volume with interpolated layers, made batch by batch (any volume size) by
// an interpolator of one batch: the GPU passes or the CPU reference.
#pragma once

#include <functional>
#include <vector>

#include "geometry/interpolation/interpolation_plan.h"

namespace scansurf {

// The batch's output layers, InterpolationBatch::outputLayers of nx * ny words, each
// label | clearance << 16, are handed to `store` (valid during that call), which may rewrite
// them and returns whether it did: what it leaves is what the interpolator keeps
// (kept_topology.h).
using BatchWords = std::function<bool(std::uint32_t* words)>;
using BatchInterpolator = std::function<Result<void>(const InterpolationBatch& batch, const BatchWords& store)>;

struct InterpolatedVolume {
  // Its labels are empty when asked for the clearances only (the labels stayed on the device).
  LabelVolume volume;
  // Per voxel, how far (1/16 of the smaller pixel spacing) its interpolated value is from
  // losing its label; a surface vertex between voxels p and q lies at c(p) / (c(p) + c(q)).
  std::vector<std::uint16_t> clearance;
};

// The volume on interpolatedGrid(volume.grid, factors): the original layers as they are, the
// others from `interpolate` with the topology of the slab rule kept in every gap
// (keepSlabTopology), in batches whose plan needs at most about batchBytes (at least two
// layers each). Without `withLabels`, only the grid and the clearances. containers: as
// planInterpolationBatch's.
Result<InterpolatedVolume> interpolateVolume(const LabelVolume& volume, const std::vector<int>& factors, std::size_t batchBytes,
                                             int threads, const BatchInterpolator& interpolate, bool withLabels = true,
                                             const std::vector<bool>& containers = {});

}  // namespace scansurf
