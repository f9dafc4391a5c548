// scansurf: the run's check of its own surfaces. Every build compares each feature's surface
// with what its contours imply: a surface that is open, not manifold or not consistently
// oriented is a defect (Engine::build refuses it, Errc::DefectiveSurface, unless
// BuildOptions::keepDefective); components, genus or volume that disagree with the contours
// are findings that name the feature with both figures, and become warnings.
#pragma once

#include <string>
#include <vector>

#include "scansurf/surfaces.h"

namespace scansurf {

enum class AuditCheck {
  Open,         // an edge with other than two triangles (defect)
  NotManifold,  // a vertex whose triangles form more than one fan (defect)
  NotOriented,  // an edge used twice in one direction (defect)
  Components,   // closed surfaces other than the contours imply
  Genus,        // handles other than the contours imply
  Volume,       // enclosed volume off the contours' slab volume by more than the tolerance
};

// A short lower-case name of the check ("open", "components", ...).
const char* auditCheckName(AuditCheck check) noexcept;

struct AuditFinding {
  int feature = -1;
  AuditCheck check = AuditCheck::Open;
  bool defect = false;  // Open, NotManifold, NotOriented
  // What the contours imply (for a range, its nearer end) and what the surface has; 0 and 1
  // for the defects.
  double expected = 0;
  double found = 0;
  std::string message;  // names the feature and both figures
};

// The topology the contours imply, as a range where a digital touch along an edge or at a
// corner may go either way (docs/method.md, "The run's audit").
struct ExpectedTopology {
  int minComponents = 0, maxComponents = 0;
  int minGenus = 0, maxGenus = 0;
  bool checked = false;  // false where the run's mode makes no such claim (partition, no region)
};

// How the audit judges (BuildOptions::audit).
struct AuditOptions {
  // A surface volume further than this fraction from the slab volume of its contours is a
  // finding (checked when smoothing restores volumes, the runs that promise them); in (0, 1].
  double volumeTolerance = 0.03;
  // true: a defective surface is kept and the build succeeds, its defects among the findings
  // (for debugging); false: Engine::build fails with Errc::DefectiveSurface.
  bool keepDefective = false;
};

struct SurfaceAudit {
  std::vector<MeshStats> stats;            // every feature's surface, in feature order
  std::vector<ExpectedTopology> expected;  // in feature order
  std::vector<double> targetVolumes;       // the slab volumes held to; empty when not checked
  double volumeTolerance = 0;              // relative
  std::vector<AuditFinding> findings;

  bool defective() const {
    for (const AuditFinding& f : findings)
      if (f.defect) return true;
    return false;
  }
};

}  // namespace scansurf
