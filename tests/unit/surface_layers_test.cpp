// Builds in several surface layers keep each feature's surface from its own layer only
// (surface_layers.h): in the enclosing convention a feature of layer 1 whose descendants are
// drawn in layer 0 also has triangles there (their union), which are not its surface.
#include "surface_layers.h"

#include <gtest/gtest.h>

namespace scansurf {
namespace {

// A layer's surfaces: one triangle per listed feature, each on vertices of its own.
Surfaces layerWith(const std::vector<int>& features, std::size_t featureCount) {
  Surfaces s;
  s.features.resize(featureCount);
  for (std::size_t f = 0; f < featureCount; ++f) s.features[f].feature = static_cast<int>(f);
  for (int f : features) {
    const auto v = static_cast<std::uint32_t>(s.mesh.vertexCount());
    s.mesh.positions.insert(s.mesh.positions.end(), {0, 0, 0, 1, 0, 0, 0, 1, 0});
    s.mesh.triangles.insert(s.mesh.triangles.end(), {v, v + 1, v + 2});
    s.mesh.labels.insert(s.mesh.labels.end(), {0, static_cast<Label>(f + 1)});
    s.features[static_cast<std::size_t>(f)].triangles = {v, v + 1, v + 2};
  }
  return s;
}

TEST(SurfaceLayers, AFeatureKeepsOnlyTheTrianglesOfItsOwnLayer) {
  OverlapReport report;
  report.features.resize(2);
  report.features[0].layer = 1;  // the container, in layer 1
  report.features[1].layer = 0;  // its descendant, in layer 0
  report.layers = 2;
  Surfaces all;
  // Layer 0: the descendant's surface, and the container's enclosing surface there (the union
  // of its descendants drawn in layer 0), which is not the container's own.
  appendLayer(all, layerWith({0, 1}, 2), report, 0);
  appendLayer(all, layerWith({0}, 2), report, 1);
  EXPECT_EQ(all.features[1].triangles.size(), 3u);
  ASSERT_EQ(all.features[0].triangles.size(), 3u);  // layer 1's only
  EXPECT_GE(all.features[0].triangles[0], 6u);      // on layer 1's vertices, after layer 0's six
}

}  // namespace
}  // namespace scansurf
