// scansurf: one feature's surface as a standalone mesh, and the plain mesh formats people open
// directly (Wavefront OBJ, binary STL), written with Draco's own encoders.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// A feature's surface with only the vertices it uses, renumbered in mesh order (the same
// numbering as writeSurfacePly), triangles wound outward.
struct CompactMesh {
  std::vector<float> positions;          // xyz per vertex, input units
  std::vector<std::uint32_t> triangles;  // 3 indices per triangle

  std::size_t vertexCount() const { return positions.size() / 3; }
  std::size_t triangleCount() const { return triangles.size() / 3; }
};

// Errors: Errc::Internal when the surface indexes a vertex beyond the mesh.
Result<CompactMesh> compactSurface(const MultiLabelMesh& mesh, const FeatureSurface& surface);

// Wavefront OBJ: `v x y z` (6 decimals, input units) and `f a b c` wound outward; `name`
// becomes the object name. Replaced atomically. Errors: Errc::Io naming the path.
Result<void> writeObj(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& name);

// Binary STL: one facet per triangle with its unit normal, float32 input units (STL has no
// unit field: viewers usually assume mm). Replaced atomically. Errors: Errc::Io naming the path.
Result<void> writeStl(const std::filesystem::path& path, const CompactMesh& mesh);

}  // namespace scansurf
