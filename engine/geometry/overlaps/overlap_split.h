// scansurf: incidental overlaps (scansurf/overlaps.h, OverlapTolerance). The separating
// surfaces give abutting structures one shared surface only when both are labelled in one
// volume (Lee et al., "Scanline Surfacing", Fig. 8); hand-drawn neighbours always overlap by a
// sliver along their interface, and that sliver must not send them to separate layers. A
// partial overlap that is thin (every shared voxel near one of the two outlines) and small
// (against both features) is incidental: the pair keeps one layer and its shared voxels are
// divided by a medial rule, each going to the feature whose own outline is farther from the
// voxel centre (in-plane distance to that feature's contours on the voxel's slice), so that
// the shared surface runs between the two drawn outlines.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "geometry/overlaps/overlap_analysis.h"

namespace scansurf {

// Marks each partial overlap of `report` incidental or not by `tolerance`, measuring depths
// (SharedVolume::depth) for the pairs small enough to be incidental.
void judgeOverlaps(const ContourSet& contours, const Grid& grid, const std::vector<FeatureRegion>& regions,
                   const OverlapTolerance& tolerance, OverlapReport& report);

// A voxel (i, j, k of the whole grid) whose surface label the medial split changes.
struct LabelOverride {
  int i = 0, j = 0, k = 0;
  Label label = kBackground;
};

// For each surface layer, the voxels shared by incidental pairs of that layer that the medial
// split gives to another feature than scan conversion's priority (Nesting::order) does. A
// voxel also inside a feature nested in one of the pair keeps the inner feature; ties go by
// priority. Fills SharedVolume::givenUpByA / givenUpByB. Deterministic.
std::vector<std::vector<LabelOverride>> splitIncidentalOverlaps(const ContourSet& contours, const Grid& grid,
                                                                const Nesting& nesting, const std::vector<FeatureRegion>& regions,
                                                                OverlapReport& report);

// Where the shared surface of an incidental pair crosses an in-plane grid edge of a contour
// plane: where the two features' signed outline distances (positive inside) are equal, the
// same rule that splits the voxels, so that the vertex sits between the two drawn outlines
// rather than on either. Used by contour fitting and by interpolation's edge crossings.
class MedialCrossings {
 public:
  MedialCrossings();
  MedialCrossings(const ContourSet& contours, const Grid& grid, const OverlapReport& report);
  MedialCrossings(MedialCrossings&&) noexcept;
  MedialCrossings& operator=(MedialCrossings&&) noexcept;
  ~MedialCrossings();

  bool empty() const;
  // Whether a and b label the two features of an incidental pair.
  bool separates(Label a, Label b) const;
  // The parameter in [0, 1] from p to q (points of the plane at z) where the medial line of the
  // features labelled a and b crosses; -1 when they are no incidental pair, z is not a contour
  // plane of both, or the line does not cross between p and q. Thread-safe.
  double crossing(Label a, Label b, double z, Point2 p, Point2 q) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The overrides as (voxel index, label) on a layer's grid, `grid` itself or a box of it on the
// same lattice (the engine's layer grids); those outside the box are left out.
std::vector<std::pair<std::size_t, Label>> overridesOnGrid(const Grid& layerGrid, const Grid& grid,
                                                           const std::vector<LabelOverride>& overrides);

}  // namespace scansurf
