// scansurf: per-feature closed surfaces selected from the shared multi-label mesh.
#pragma once

#include <vector>

#include "scansurf/nesting.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// One surface per feature 0..featureCount-1 (feature f carries label f+1), as triangles of
// `mesh` (indices shared, so abutting surfaces share vertices), in mesh triangle order and
// oriented outward.
// Partition: the triangles with label f+1 on one side, flipped where f+1 is the larger label.
// Enclosing: with E = {f} and every feature g where isInside(nesting, g, f), the triangles
// with exactly one side's feature in E, flipped where that side is the larger label.
// Labels of features >= featureCount count as outside every set. A feature with no voxels
// (and, for Enclosing, no nested features with voxels) gets an empty surface.
std::vector<FeatureSurface> extractFeatureSurfaces(const MultiLabelMesh& mesh, int featureCount, const Nesting& nesting,
                                                   SurfaceConvention convention);

}  // namespace scansurf
