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

// Compacts the surfaces of one shared mesh, one after another. Holds one index per mesh
// vertex, set up once, so each surface then costs O(k + u log u) for k indices and u distinct
// vertices: compacting thousands of small features stays linear overall.
class SurfaceCompactor {
 public:
  explicit SurfaceCompactor(const MultiLabelMesh& mesh);
  // The surface's vertices in their shared-mesh order. Errors: Errc::Internal when the
  // surface indexes a vertex beyond the mesh.
  Result<CompactMesh> compact(const FeatureSurface& surface);

 private:
  const MultiLabelMesh& mesh_;
  std::vector<std::uint32_t> remap_;  // kUnused except while a surface is being compacted
  std::vector<std::uint32_t> used_;
};

// Area-weighted vertex normals of a closed, outward surface (smooth within the feature), xyz
// per vertex; (0, 0, 1) for a vertex of no area.
std::vector<float> vertexNormals(const CompactMesh& mesh);

// One surface on its own (O(mesh vertices) set-up; to compact many, reuse a SurfaceCompactor).
Result<CompactMesh> compactSurface(const MultiLabelMesh& mesh, const FeatureSurface& surface);

}  // namespace scansurf
