// scansurf: one feature's surface as a standalone mesh (see compact_mesh.h).
#include "geometry/mesh/compact_mesh.h"

#include <cmath>

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

std::vector<float> vertexNormals(const CompactMesh& mesh) {
  std::vector<double> sum(mesh.positions.size(), 0.0);
  const auto at = [&](std::uint32_t v, int axis) { return static_cast<double>(mesh.positions[3 * std::size_t{v} + axis]); };
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::uint32_t a = mesh.triangles[3 * t], b = mesh.triangles[3 * t + 1], c = mesh.triangles[3 * t + 2];
    const double u[3] = {at(b, 0) - at(a, 0), at(b, 1) - at(a, 1), at(b, 2) - at(a, 2)};
    const double w[3] = {at(c, 0) - at(a, 0), at(c, 1) - at(a, 1), at(c, 2) - at(a, 2)};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    for (std::uint32_t v : {a, b, c})
      for (int axis = 0; axis < 3; ++axis) sum[3 * std::size_t{v} + axis] += n[axis];
  }
  std::vector<float> normals(sum.size());
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    const double length = std::hypot(sum[3 * v], sum[3 * v + 1], sum[3 * v + 2]);
    for (int axis = 0; axis < 3; ++axis)
      normals[3 * v + axis] = length > 0 ? static_cast<float>(sum[3 * v + axis] / length) : (axis == 2 ? 1.0f : 0.0f);
  }
  return normals;
}

}  // namespace scansurf
