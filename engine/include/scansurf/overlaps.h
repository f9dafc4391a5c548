// scansurf: structures that overlap by design (planning volumes over organs, margins, skin
// marks outside BODY) and what each feature's volume is, three ways.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace scansurf {

struct Grid;  // scansurf/grid.h

enum class OverlapMode {
  // Default: features are assigned to the fewest layers such that no two features of a layer
  // partly overlap (incidental overlaps aside: OverlapTolerance), and each layer is surfaced on its own; every feature's surface
  // encloses its
  // own contours' region. Abutting features of one layer share their interface; surfaces of
  // different layers may intersect exactly as their contours do.
  Layers,
  // One label per voxel (the seed's method): no two surfaces ever intersect; where features
  // partly overlap, the one of higher priority (nesting order) takes the shared voxels.
  Partition,
};

// When a partial overlap is incidental rather than by design. Hand-drawn neighbours always
// overlap by a sliver along their interface (two outlines are never drawn on the same line),
// and now and then by a stray bump. A pair's overlap is incidental when it is small (at most
// `percent` of the smaller feature in all) and each connected region of its shared voxels is
// thin (every voxel of it lies near one of the two outlines) or tiny (at most half `percent`)
// whatever its depth: the medial split then moves less than that share of either feature.
// An incidental pair stays in one layer, sharing its interface,
// and the shared voxels are divided between the two: each goes to the feature whose own
// outline is farther from it (a medial split), so the shared surface runs between the two
// drawn outlines. A pair with any other region overlaps for real: it goes to separate layers.
struct OverlapTolerance {
  // false: every shared voxel between features not nested in one another means layers.
  bool enabled = true;
  // The deepest shared voxel's in-plane distance to the nearer of the two outlines, at most
  // this (input units). 0 = automatic: the larger of two pixels (the grid's larger pixel side)
  // and half the median spacing of the contour planes, so the verdict does not hinge on a fine
  // in-plane grid (a drawn outline is no more precise in-plane than about that).
  double depth = 0;
  // The shared volume, at most this percentage of the smaller feature's own volume; a region
  // deeper than `depth`, at most half of it.
  double percent = 2.0;
};

// The depth limit `tolerance` sets on a grid (input units).
double incidentalDepthLimit(const OverlapTolerance& tolerance, const Grid& grid);

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
  // Partial overlaps, with the rule on: the deepest shared voxel's distance to the nearer of the
  // two outlines (input units); measured only for pairs whose regions are all small enough to
  // be incidental, and then only up to the depth limit (depthMeasured false: not measured, or
  // deeper than that).
  double depth = 0;
  bool depthMeasured = false;
  int regions = 0;           // connected regions of the shared voxels (partial overlaps, rule on)
  double largestRegion = 0;  // the largest one's volume
  bool incidental = false;   // every region thin and small, or tiny (OverlapTolerance)
  // Incidental pairs in Layers mode: the shared volume whose surface went to the other
  // feature (what a gave up to b, and b to a).
  double givenUpByA = 0;
  double givenUpByB = 0;
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
  std::vector<FeatureVolumes> features;       // one per input feature
  std::vector<SharedVolume> shared;           // every pair sharing voxels
  std::vector<std::pair<int, int>> touching;  // pairs whose regions abut without sharing voxels
  int layers = 1;                             // surface layers
  int maskLayers = 1;                         // label volume layers (nested features apart too)
  std::vector<VolumeLoss> losses;             // Partition mode only
  OverlapTolerance tolerance;                 // the rule the verdicts used

  // Partly overlapping pairs (shared and not nested), incidental ones included.
  std::vector<SharedVolume> partialOverlaps() const {
    std::vector<SharedVolume> out;
    for (const SharedVolume& s : shared)
      if (!s.nested) out.push_back(s);
    return out;
  }
  // Overlaps by design: partial and not incidental (separate layers in Layers mode).
  std::vector<SharedVolume> realOverlaps() const {
    std::vector<SharedVolume> out;
    for (const SharedVolume& s : shared)
      if (!s.nested && !s.incidental) out.push_back(s);
    return out;
  }
};

}  // namespace scansurf
