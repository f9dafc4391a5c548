// Feature surfaces as subsets of the shared separating-surface mesh (Nielson & Franke 1997):
// every union of label regions is bounded by the mesh triangles with exactly one side in it.
#include "geometry/extraction/feature_surfaces.h"

#include <algorithm>

namespace scansurf {
namespace {

void appendTriangle(FeatureSurface& s, const std::uint32_t* t, bool flip) {
  s.triangles.push_back(t[0]);
  s.triangles.push_back(flip ? t[2] : t[1]);
  s.triangles.push_back(flip ? t[1] : t[2]);
}

}  // namespace

std::vector<FeatureSurface> extractFeatureSurfaces(const MultiLabelMesh& mesh, int featureCount, const Nesting& nesting,
                                                   SurfaceConvention convention) {
  std::vector<FeatureSurface> surfaces(static_cast<std::size_t>(std::max(featureCount, 0)));
  for (int f = 0; f < featureCount; ++f) surfaces[static_cast<std::size_t>(f)].feature = f;
  auto featureOf = [&](Label label) {
    const int f = featureOfLabel(label);
    return f >= 0 && f < featureCount ? f : -1;
  };
  const std::size_t triangleCount = mesh.triangleCount();

  if (convention == SurfaceConvention::Partition) {
    for (std::size_t t = 0; t < triangleCount; ++t) {
      const std::uint32_t* tri = &mesh.triangles[3 * t];
      // Triangles point from a into b: outward for a, inward for b.
      if (const int fa = featureOf(mesh.labels[2 * t]); fa >= 0) appendTriangle(surfaces[fa], tri, false);
      if (const int fb = featureOf(mesh.labels[2 * t + 1]); fb >= 0) appendTriangle(surfaces[fb], tri, true);
    }
    return surfaces;
  }

  // Enclosing: containers[g] = the features f whose set E holds g (g and everything g lies
  // inside), sorted; only for features present in the mesh.
  std::vector<char> present(surfaces.size(), 0);
  for (Label l : mesh.labels)
    if (const int f = featureOf(l); f >= 0) present[static_cast<std::size_t>(f)] = 1;
  std::vector<std::vector<int>> containers(surfaces.size());
  for (int g = 0; g < featureCount; ++g) {
    if (!present[static_cast<std::size_t>(g)]) continue;
    for (int f = 0; f < featureCount; ++f)
      if (f == g || isInside(nesting, g, f)) containers[static_cast<std::size_t>(g)].push_back(f);
  }
  static const std::vector<int> kNone;
  for (std::size_t t = 0; t < triangleCount; ++t) {
    const std::uint32_t* tri = &mesh.triangles[3 * t];
    const int fa = featureOf(mesh.labels[2 * t]);
    const int fb = featureOf(mesh.labels[2 * t + 1]);
    const std::vector<int>& inA = fa >= 0 ? containers[static_cast<std::size_t>(fa)] : kNone;
    const std::vector<int>& inB = fb >= 0 ? containers[static_cast<std::size_t>(fb)] : kNone;
    // Sets holding exactly one side: a's side inside keeps the winding, b's side flips it.
    std::size_t i = 0, j = 0;
    while (i < inA.size() || j < inB.size()) {
      if (j == inB.size() || (i < inA.size() && inA[i] < inB[j])) {
        appendTriangle(surfaces[static_cast<std::size_t>(inA[i++])], tri, false);
      } else if (i == inA.size() || inB[j] < inA[i]) {
        appendTriangle(surfaces[static_cast<std::size_t>(inB[j++])], tri, true);
      } else {
        ++i;
        ++j;
      }
    }
  }
  return surfaces;
}

}  // namespace scansurf
