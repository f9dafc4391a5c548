// scansurf: each vertex's triangles in a multi-label mesh, as one list (smoothing's adjacency,
// volume restoration's gradients).
#pragma once

#include <cstdint>

#include "core/huge_pages.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// Each vertex's triangles, as offsets (size V + 1) into one list, in ascending order.
struct IncidentTriangles {
  HugeVector<std::uint32_t> start, list;
};

IncidentTriangles incidentTriangles(const MultiLabelMesh& mesh);

}  // namespace scansurf
