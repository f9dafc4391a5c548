// scansurf: one feature's surface as a standalone mesh (see compact_mesh.h).
#include "geometry/compact_mesh.h"

#include <algorithm>
#include <limits>
#include <string>

namespace scansurf {
namespace {
constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
}

SurfaceCompactor::SurfaceCompactor(const MultiLabelMesh& mesh) : mesh_(mesh), remap_(mesh.vertexCount(), kUnused) {}

Result<CompactMesh> SurfaceCompactor::compact(const FeatureSurface& surface) {
  used_.clear();
  for (std::uint32_t v : surface.triangles) {
    if (v >= remap_.size()) {
      for (std::uint32_t u : used_) remap_[u] = kUnused;
      return makeError(Errc::Internal, "surface of feature " + std::to_string(surface.feature) + " indexes vertex " +
                                           std::to_string(v) + " beyond the mesh's " + std::to_string(remap_.size()));
    }
    if (remap_[v] == kUnused) {
      remap_[v] = 0;
      used_.push_back(v);
    }
  }
  std::sort(used_.begin(), used_.end());  // keep the shared mesh's vertex order
  CompactMesh out;
  out.positions.reserve(3 * used_.size());
  for (std::size_t i = 0; i < used_.size(); ++i) {
    const std::uint32_t v = used_[i];
    remap_[v] = static_cast<std::uint32_t>(i);
    out.positions.insert(out.positions.end(), mesh_.positions.begin() + 3 * static_cast<std::ptrdiff_t>(v),
                         mesh_.positions.begin() + 3 * static_cast<std::ptrdiff_t>(v) + 3);
  }
  out.triangles.reserve(surface.triangles.size());
  for (std::uint32_t v : surface.triangles) out.triangles.push_back(remap_[v]);
  for (std::uint32_t v : used_) remap_[v] = kUnused;
  return out;
}

Result<CompactMesh> compactSurface(const MultiLabelMesh& mesh, const FeatureSurface& surface) {
  return SurfaceCompactor(mesh).compact(surface);
}

}  // namespace scansurf
