// scansurf passes: multi-label shape-based interpolation on the GPU (Grevera & Udupa 1996;
// the rule in geometry/interpolation_plan.h). Per slab, three compute passes with no host
// round trip between them: the rows of every label's distance field, its columns (exact
// Euclidean distances, Felzenszwalb & Huttenlocher 2012), then the labels of the interpolated
// layers. Identical, voxel for voxel, to geometry/interpolation_reference.h.
#pragma once

#include <memory>
#include <vector>

#include "geometry/interpolated_volume.h"
#include "gpu/context.h"

namespace scansurf::passes {

class Interpolator {
 public:
  static Result<std::unique_ptr<Interpolator>> create(const gpu::Context& ctx);
  ~Interpolator();

  // The volume on interpolatedGrid(volume.grid, factors) (see interpolated_volume.h);
  // crossings: planeEdgeCrossings of the volume (geometry/edge_crossings.h).
  Result<InterpolatedVolume> run(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings, const std::vector<int>& factors,
                                 CapShape caps, int threads);
  // One slab's output layers, handed to `store` (InterpolationSlab::outputLayers of nx * ny
  // label | clearance << 16 words, read straight from the device's readback buffer).
  Result<void> runSlab(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings, const InterpolationSlab& slab,
                       const DistanceWeights& weights, CapShape caps, const SlabWords& store);

  // Bytes one slab may use on the device; smaller forces more slabs (tests use it).
  void setSlabBudget(std::size_t bytes);
  int lastSlabCount() const;

  struct State;

 private:
  explicit Interpolator(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace scansurf::passes
