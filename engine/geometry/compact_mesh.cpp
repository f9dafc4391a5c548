#include "geometry/compact_mesh.h"

#include <algorithm>
#include <string>

namespace scansurf {

Result<CompactMesh> compactSurface(const MultiLabelMesh& mesh, const FeatureSurface& surface) {
  std::vector<std::uint32_t> used(surface.triangles);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  if (!used.empty() && used.back() >= mesh.vertexCount())
    return makeError(Errc::Internal, "surface of feature " + std::to_string(surface.feature) + " indexes vertex " +
                                         std::to_string(used.back()) + " beyond the mesh's " +
                                         std::to_string(mesh.vertexCount()));
  CompactMesh out;
  out.positions.reserve(3 * used.size());
  for (std::uint32_t v : used)
    out.positions.insert(out.positions.end(), mesh.positions.begin() + 3 * static_cast<std::ptrdiff_t>(v),
                         mesh.positions.begin() + 3 * static_cast<std::ptrdiff_t>(v) + 3);
  out.triangles.reserve(surface.triangles.size());
  for (std::uint32_t v : surface.triangles)
    out.triangles.push_back(static_cast<std::uint32_t>(std::lower_bound(used.begin(), used.end(), v) - used.begin()));
  return out;
}

}  // namespace scansurf
