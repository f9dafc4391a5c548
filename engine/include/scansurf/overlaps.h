// scansurf: structures that overlap by design (planning volumes over organs, margins, skin
// marks outside BODY) and what each feature's volume is, three ways.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace scansurf {

enum class OverlapMode {
  // Default: features are assigned to the fewest layers such that no two features of a layer
  // partly overlap, and each layer is surfaced on its own; every feature's surface encloses its
  // own contours' region. Abutting features of one layer share their interface; surfaces of
  // different layers may intersect exactly as their contours do.
  Layers,
  // One label per voxel (the seed's method): no two surfaces ever intersect; where features
  // partly overlap, the one of higher priority (nesting order) takes the shared voxels.
  Partition,
};

// "layers" or "partition"; nullopt otherwise.
std::optional<OverlapMode> parseOverlapMode(std::string_view name);
const char* overlapModeName(OverlapMode mode);

// A feature's volume three ways (input units cubed) and where it went.
struct FeatureVolumes {
  // Sum over its planes of the even-odd area of its contours times the plane's slab: half the
  // distance to the layer below plus half the distance to the layer above (the surface closes
  // half a slab beyond the first and last plane, at the neighbouring layer spacing).
  double contour = 0;
  std::size_t ownVoxels = 0;  // voxels whose centres its own contours enclose (alone)
  double ownVolume = 0;       // their volume: the labelled voxel volume
  int layer = 0;              // surface layer (Layers mode); 0 in Partition mode
  int maskLayer = 0;          // layer of its own mask in the label volume file
};

// Two features sharing voxels: a partial overlap, or one nested in the other.
struct SharedVolume {
  int a = 0;  // a < b, feature indices
  int b = 0;
  std::size_t voxels = 0;
  double volume = 0;
  bool nested = false;  // one contains the other (Nesting): not an overlap in the enclosing convention
};

// Partition mode: voxels of `feature`'s own region labelled with the higher-priority `to`.
struct VolumeLoss {
  int feature = 0;
  int to = 0;
  std::size_t voxels = 0;
  double volume = 0;
  bool nested = false;  // `feature` contains `to`: the partition convention's container shell
};

struct OverlapReport {
  OverlapMode mode = OverlapMode::Layers;
  std::vector<FeatureVolumes> features;        // one per input feature
  std::vector<SharedVolume> shared;            // every pair sharing voxels
  std::vector<std::pair<int, int>> touching;   // pairs whose regions abut without sharing voxels
  int layers = 1;                              // surface layers
  int maskLayers = 1;                          // label volume layers (nested features apart too)
  std::vector<VolumeLoss> losses;              // Partition mode only

  // Partly overlapping pairs (shared and not nested).
  std::vector<SharedVolume> partialOverlaps() const {
    std::vector<SharedVolume> out;
    for (const SharedVolume& s : shared)
      if (!s.nested) out.push_back(s);
    return out;
  }
};

}  // namespace scansurf
