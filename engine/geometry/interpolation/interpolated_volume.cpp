// scansurf: interpolated label volumes batch by batch (see interpolated_volume.h).
#include "geometry/interpolation/interpolated_volume.h"

#include <algorithm>
#include <cstring>

#include "geometry/interpolation/kept_topology.h"

namespace scansurf {
namespace {

// A batch from layer `first` as long as its plan stays within the budget (two layers at least):
// as many planes as the estimate lets in, fewer if the plan turns out larger.
InterpolationBatch planBatch(const LabelVolume& volume, const PlaneCensus& census, int first, const std::vector<int>& factors,
                             std::size_t batchBytes, const std::vector<bool>& containers) {
  int planes = 0;
  std::size_t estimate = 0;
  while (first + planes < volume.grid.nz) {
    const int k = first + planes;
    estimate += estimatePlaneBytes(volume, census, k, k < volume.grid.nz - 1 ? factors[static_cast<std::size_t>(k)] : 1);
    if (planes >= 2 && estimate > batchBytes) break;
    ++planes;
  }
  for (;;) {
    InterpolationBatch batch = planInterpolationBatch(volume, census, first, planes, factors, containers);
    const std::size_t bytes = batch.deviceBytes(volume.grid);
    if (bytes <= batchBytes || planes <= 2) return batch;
    const double fit = static_cast<double>(batchBytes) / static_cast<double>(bytes);
    planes = std::max(2, std::min(planes - 1, static_cast<int>(planes * fit * 0.9)));
  }
}

// A voxel left at the slab rule's label gets a clearance of one pixel: the surface between it
// and a neighbour of another label then lies near that neighbour.
constexpr std::uint16_t kKeptClearance = 16;

// keepSlabTopology on one pair's layers of the batch's words; the voxels it relabelled.
std::size_t keepTopologyOfPair(std::uint32_t* words, const LabelVolume& volume, const shared::PairPlan& pair, int planeA) {
  const Grid& g = volume.grid;
  const std::size_t plane = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  std::uint32_t* layers = words + plane * static_cast<std::size_t>(pair.firstLayer);
  const Label* lower = volume.labels.data() + plane * static_cast<std::size_t>(planeA);
  return keepSlabTopology(layers, lower, lower + plane, g.nx, g.ny, pair.factor, kKeptClearance);
}

}  // namespace

// Labels of the layers between the pair's planes, and the clearance of all its layers.
void storePair(const std::uint32_t* words, const shared::PairPlan& pair, std::size_t plane, int fineA, InterpolatedVolume& out) {
  for (int m = 0; m < pair.layers; ++m) {
    const std::uint32_t* in = words + plane * static_cast<std::size_t>(pair.firstLayer + m);
    const std::size_t at = plane * static_cast<std::size_t>(fineA + m);
    Label* labels = out.volume.labels.empty() ? nullptr : out.volume.labels.data() + at;
    std::uint16_t* clearance = out.clearance.data() + at;
    const bool interpolated = labels && m > 0 && m < pair.factor;
    for (std::size_t i = 0; i < plane; ++i) {
      if (interpolated) labels[i] = static_cast<Label>(in[i] & 0xFFFFu);
      clearance[i] = static_cast<std::uint16_t>(in[i] >> 16);
    }
  }
}

Result<InterpolatedVolume> interpolateVolume(const LabelVolume& volume, const std::vector<int>& factors, std::size_t batchBytes,
                                             int threads, const BatchInterpolator& interpolate, bool withLabels,
                                             const std::vector<bool>& containers) {
  const Grid& g = volume.grid;
  if (factors.size() + 1 != static_cast<std::size_t>(g.nz))
    return makeError(Errc::InvalidArgument, "interpolation: one factor per gap between layers is needed");
  InterpolatedVolume out;
  LabelVolume& fine = out.volume;
  fine.grid = interpolatedGrid(g, factors);
  const std::size_t plane = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  const std::vector<int> fineOf = fineLayerOfPlane(factors);
  if (withLabels || !interpolates(factors)) {
    fine.labels.assign(fine.grid.voxelCount(), kBackground);
    for (int k = 0; k < g.nz; ++k)
      std::memcpy(fine.labels.data() + plane * static_cast<std::size_t>(fineOf[static_cast<std::size_t>(k)]),
                  volume.labels.data() + plane * static_cast<std::size_t>(k), plane * sizeof(Label));
  }
  if (!interpolates(factors)) return out;
  out.clearance.assign(fine.grid.voxelCount(), 0);

  const PlaneCensus census = takePlaneCensus(volume, threads);
  for (int first = 0; first + 1 < g.nz;) {
    const InterpolationBatch batch = planBatch(volume, census, first, factors, batchBytes, containers);
    if (batch.outputLayers > 0) {
      SCANSURF_TRY(interpolate(batch, [&](std::uint32_t* words) {
        std::size_t relabelled = 0;
        for (const shared::PairPlan& pair : batch.pairs)
          relabelled += keepTopologyOfPair(words, volume, pair, batch.firstPlane + pair.planeA);
        for (const shared::PairPlan& pair : batch.pairs)
          storePair(words, pair, plane, fineOf[static_cast<std::size_t>(batch.firstPlane + pair.planeA)], out);
        return relabelled > 0;
      }));
    }
    first = batch.lastPairPlane();
  }
  return out;
}

}  // namespace scansurf
