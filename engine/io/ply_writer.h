// scansurf: binary little-endian PLY output of separating surfaces.
#pragma once

#include <filesystem>

#include "geometry/mesh/compact_mesh.h"
#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// Writes one feature's surface: only the vertices it uses, renumbered in mesh order, as
// float x, y, z (input units), and its triangles as `uchar 3, int i0, i1, i2`, wound outward.
// The file is replaced atomically. Errors: Errc::Io naming the path.
Result<void> writeSurfacePly(const std::filesystem::path& path, const MultiLabelMesh& mesh, const FeatureSurface& surface,
                             const std::string& units = {});
// The same from a surface already compacted (geometry/mesh/compact_mesh.h); `feature` names it in
// the header.
Result<void> writeSurfacePly(const std::filesystem::path& path, const CompactMesh& surface, int feature,
                             const std::string& units = {});

// Writes the whole multi-label mesh: every vertex, and each face with `ushort label_inside,
// ushort label_outside` (the labels a < b; the face's normal points from a's region into b's;
// label 0 is background, label L is feature L-1). The file is replaced atomically.
// Errors: Errc::Io naming the path.
Result<void> writeMultiLabelPly(const std::filesystem::path& path, const MultiLabelMesh& mesh, const std::string& units = {});

}  // namespace scansurf
