// scansurf: each vertex's triangles (see incident_triangles.h).
#include "geometry/mesh/incident_triangles.h"

namespace scansurf {

IncidentTriangles incidentTriangles(const MultiLabelMesh& mesh) {
  const std::size_t vertexCount = mesh.vertexCount(), triangleCount = mesh.triangleCount();
  IncidentTriangles in{HugeVector<std::uint32_t>(vertexCount + 1, 0), HugeVector<std::uint32_t>(3 * triangleCount)};
  for (std::uint32_t v : mesh.triangles) ++in.start[v + 1];
  for (std::size_t v = 0; v < vertexCount; ++v) in.start[v + 1] += in.start[v];
  HugeVector<std::uint32_t> fill(in.start.begin(), in.start.end() - 1);
  for (std::size_t t = 0; t < triangleCount; ++t)
    for (int c = 0; c < 3; ++c) in.list[fill[mesh.triangles[3 * t + c]]++] = static_cast<std::uint32_t>(t);
  return in;
}

}  // namespace scansurf
