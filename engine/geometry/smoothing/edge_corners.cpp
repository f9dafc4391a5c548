#include "geometry/smoothing/edge_corners.h"

#include "core/parallel.h"
#include "geometry/smoothing/contour_fit.h"

namespace scansurf {

std::vector<EdgeCorners> edgeCornersOf(const MultiLabelMesh& mesh, int threads) {
  std::vector<EdgeCorners> out(mesh.vertexCount());
  parallelChunks(out.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
      if (const Carrier c = carrierOfKey(mesh.keys[v]); c.count == 2) out[v] = {cornerKey(c.corners[0]), cornerKey(c.corners[1])};
  });
  return out;
}

}  // namespace scansurf
