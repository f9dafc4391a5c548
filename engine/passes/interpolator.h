// scansurf passes: multi-label shape-based interpolation on the GPU (Grevera & Udupa 1996;
// the rule in geometry/interpolation/interpolation_plan.h). Per batch, three compute passes with no host
// round trip between them: the rows of every label's distance field, its columns (exact
// Euclidean distances, Felzenszwalb & Huttenlocher 2012), then the labels of the interpolated
// layers. Identical, voxel for voxel, to geometry/interpolation/interpolation_reference.h.
#pragma once

#include <memory>
#include <vector>

#include "geometry/interpolation/interpolated_volume.h"
#include "gpu/context.h"
#include "gpu/resources.h"

namespace scansurf::passes {

// What of an interpolation stays on the device: `planes`, the same labels as the
// planes volume in a buffer of 16-bit labels (ScanConverter::runOnDevice), copied there into
// each batch instead of uploaded; `words` (at least 4 bytes per voxel of the interpolated grid)
// receives every voxel's word, label | clearance << 16 (the contour planes' own labels on
// their layers), to be classified there (Classifier::runInPlace, upper half as data).
struct InterpolationDeviceIo {
  const gpu::Buffer* planes = nullptr;
  const gpu::Buffer* words = nullptr;
  VkDeviceSize wordsOffset = 0;  // runBatch: where the batch's first output layer goes
};

class Interpolator {
 public:
  static Result<std::unique_ptr<Interpolator>> create(const gpu::Context& ctx);
  ~Interpolator();

  // The volume on interpolatedGrid(volume.grid, factors) (see interpolated_volume.h);
  // crossings: planeEdgeCrossings of the volume (geometry/extraction/edge_crossings.h). With device
  // words, the host gets the clearances only (the volume's labels stay empty). containers: as
  // planInterpolationBatch's (geometry/interpolation/interpolation_plan.h).
  Result<InterpolatedVolume> run(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings,
                                 const std::vector<int>& factors, CapShape caps, int threads, InterpolationDeviceIo device = {},
                                 const std::vector<bool>& containers = {});
  // One batch's output layers, handed to `store` (InterpolationBatch::outputLayers of nx * ny
  // label | clearance << 16 words, read straight from the device's readback buffer).
  Result<void> runBatch(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings, const InterpolationBatch& batch,
                        const DistanceWeights& weights, CapShape caps, int threads, const BatchWords& store,
                        const InterpolationDeviceIo& device = {});

  // Bytes one batch may use on the device; smaller forces more batches (tests use it).
  void setBatchBudget(std::size_t bytes);
  int lastBatchCount() const;

  struct State;

 private:
  explicit Interpolator(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace scansurf::passes
