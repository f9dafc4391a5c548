#include "geometry/shape/triangle_shape.h"

#include <chrono>

#include "geometry/shape/quad_diagonals.h"
#include "geometry/shape/snapping.h"

namespace scansurf {

ShapedTriangles shapeTriangles(MultiLabelMesh& mesh, const Grid& grid, double snapFraction, std::vector<bool>& onSheet,
                               bool cubeFans, int threads) {
  const auto start = std::chrono::steady_clock::now();
  ShapedTriangles out;
  out.report = snapToLattice(mesh, grid, snapFraction, onSheet, threads);
  out.report.quadsFlipped = chooseQuadDiagonals(mesh, threads);
  if (cubeFans) out.disks = retriangulateCubeFans(mesh, grid, onSheet, threads);
  out.report.cubeFans = out.disks.count(), out.report.fanVerticesRemoved = out.disks.removedVertices;
  out.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace scansurf
