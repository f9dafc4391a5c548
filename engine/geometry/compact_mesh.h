// scansurf: one feature's surface as a standalone mesh (only the vertices it uses).
#pragma once

#include <cstdint>
#include <vector>

#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// A feature's surface with only the vertices it uses, renumbered in mesh order, triangles
// wound outward.
struct CompactMesh {
  std::vector<float> positions;          // xyz per vertex, input units
  std::vector<std::uint32_t> triangles;  // 3 indices per triangle

  std::size_t vertexCount() const { return positions.size() / 3; }
  std::size_t triangleCount() const { return triangles.size() / 3; }
};

// Extracts the surface's vertices, keeping their order in the shared mesh. Costs
// O(k log k) in the surface's own size k, not in the shared mesh's, so writing thousands of
// small features stays linear overall. Errors: Errc::Internal when the surface indexes a
// vertex beyond the mesh.
Result<CompactMesh> compactSurface(const MultiLabelMesh& mesh, const FeatureSurface& surface);

}  // namespace scansurf
