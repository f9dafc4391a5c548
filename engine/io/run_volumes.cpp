// scansurf: the label volumes a run writes (see run_volumes.h), and labelImage (scansurf/outputs.h).
#include "io/run_volumes.h"

#include "geometry/overlaps/label_layers.h"
#include "geometry/overlaps/overlap_analysis.h"
#include "geometry/overlaps/own_slabs.h"
#include "scansurf/outputs.h"

#include <cmath>

namespace scansurf {
namespace {

// Cuts a volume to the reference lattice; per feature, the voxels dropped.
Result<RegularLabelVolume> onReference(const LabelVolume& volume, const GridReference& reference, std::size_t features,
                                       std::vector<std::size_t>* dropped) {
  SCANSURF_ASSIGN_OR_RETURN(ReferenceCut cut, cutToReference(volume, reference, features));
  if (dropped)
    for (std::size_t f = 0; f < features; ++f) (*dropped)[f] += cut.dropped[f];
  return regularize(cut.volume);
}

}  // namespace

Result<RunVolumes> runVolumes(const ContourSet& input, const BuildResult& built, bool withPartition) {
  const Grid& grid = built.volume.grid;
  // The masks hold each feature's own slabs on the other features' planes, as the surfaces do.
  const std::optional<ContourSet> filled = withOwnSlabs(input, grid, built.gapFactor);
  const ContourSet& contours = filled ? *filled : input;
  const std::size_t n = contours.features.size();
  if (built.overlaps.features.size() != n)
    return makeError(Errc::InvalidArgument, "label volume: the build result is not that of the contour set");
  const std::vector<FeatureRegion> regions = rasterizeFeatures(contours, grid, built.subPixelBits, 0);
  RunVolumes out;
  out.masksOnGrid = maskLayerVolumes(regions, grid, built.overlaps);
  for (const FeatureVolumes& f : built.overlaps.features) out.maskLayerOf.push_back(f.maskLayer);
  // The partition only for a file that holds one (NIfTI): it is another whole volume.
  const LabelVolume partition = withPartition ? partitionVolume(regions, grid, built.nesting.order) : LabelVolume{};
  // Only a grid built on the reference lattice (no --voxel-size / --grid of its own) is cut to it.
  const bool onLattice = contours.reference && std::abs(grid.spacingX - contours.reference->spacingX) <= 1e-9 * grid.spacingX &&
                         std::abs(grid.spacingY - contours.reference->spacingY) <= 1e-9 * grid.spacingY;
  if (contours.reference && !onLattice)
    out.warnings.push_back(
        "the label volume lies on the run's grid, not on the reference CT's (a voxel size or pixel "
        "counts of its own were given)");
  if (!onLattice) {
    for (const LabelVolume& m : out.masksOnGrid) out.masks.push_back(regularize(m));
    if (withPartition) out.partition = regularize(partition);
    return out;
  }
  std::vector<std::size_t> dropped(n, 0);
  for (const LabelVolume& m : out.masksOnGrid) {
    SCANSURF_ASSIGN_OR_RETURN(RegularLabelVolume cut, onReference(m, *contours.reference, n, &dropped));
    out.masks.push_back(std::move(cut));
  }
  if (withPartition) {
    SCANSURF_ASSIGN_OR_RETURN(out.partition, onReference(partition, *contours.reference, n, nullptr));
  }
  for (std::size_t f = 0; f < n; ++f)
    if (dropped[f] > 0)
      out.warnings.push_back("feature \"" + contours.features[f].name + "\": " + std::to_string(dropped[f]) +
                             " voxel(s) beyond the reference CT are not in the label volume (it lies on the CT's grid)");
  return out;
}

Result<LabelImage> labelImage(const ContourSet& contours, const BuildResult& built) {
  SCANSURF_ASSIGN_OR_RETURN(RunVolumes volumes, runVolumes(contours, built, true));
  RegularLabelVolume& p = volumes.partition;
  LabelImage image{
      p.nx, p.ny, p.nz, std::move(p.labels), p.geometry.origin, p.geometry.axes, p.resampled, std::move(volumes.warnings)};
  return image;
}

}  // namespace scansurf
