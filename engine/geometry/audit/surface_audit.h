// scansurf: each feature's surface held to what its contours imply (scansurf/audit.h): closed,
// manifold and oriented; components and genus within the contours' topology range
// (contour_topology.h); volume near its slab volume.
#pragma once

#include <span>
#include <vector>

#include "geometry/overlaps/overlap_analysis.h"
#include "scansurf/audit.h"
#include "scansurf/contours.h"

namespace scansurf {

struct AuditInputs {
  const ContourSet& contours;
  const Surfaces& surfaces;
  std::span<const FeatureRegion> regions;  // per feature; empty: topology not checked
  std::vector<double> targetVolumes;       // per feature; empty: volumes not checked
  double volumeTolerance = 0.03;
  double volumeFloor = 0;  // differences under this (input units cubed) are never findings
  int threads = 0;
};

SurfaceAudit auditSurfaces(const AuditInputs& in);

}  // namespace scansurf
