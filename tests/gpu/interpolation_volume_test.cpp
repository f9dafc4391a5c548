// Volumes between the slices: with interpolation (the CLI's default, round caps), structures
// of one, two and three planes keep their contour volume (the slab rule), because each round
// cap is a dome as high as the gap that holds a flat half slab's volume.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "gpu/gpu_test_env.h"
#include "support/shapes.h"

namespace scansurf::test {
namespace {

Contour ellipse(Point2 c, double a, double b) { return ellipseContour(c, a, b, 128); }

Feature onPlanes(const std::string& name, const Contour& contour, std::initializer_list<double> zs) {
  Feature f{name, {}, {}};
  for (double z : zs) f.slices.push_back({z, {contour}});
  return f;
}

// BODY on ten planes 2 mm apart holding: a disc on one plane mid-stack, a disc on two planes, a
// thin scar on two, a disc on three, and a disc on the stack's first plane only.
ContourSet smallStructures() {
  ContourSet set;
  set.source = "small structures";
  Feature body{"BODY", {}, {}};
  for (int k = 0; k < 10; ++k) body.slices.push_back({2.0 * k, {circleContour({0, 0}, 40)}});
  set.features = {std::move(body),
                  onPlanes("one", circleContour({-15, 0}, 6), {8}),
                  onPlanes("two", circleContour({15, 0}, 5), {8, 10}),
                  onPlanes("scar", ellipse({0, 20}, 12, 1.5), {8, 10}),
                  onPlanes("three", circleContour({0, -20}, 7), {6, 8, 10}),
                  onPlanes("first", circleContour({-20, -20}, 5), {0})};
  return set;
}

class InterpolationVolumeTest : public EngineTest {
 protected:
  static BuildResult build(const ContourSet& set, double voxelSize, int factor = InterpolationOptions::kAuto) {
    BuildOptions options;
    options.grid.voxelSize = voxelSize;
    options.interpolation.factor = factor;
    options.smoothing.enabled = true;
    auto built = engine_->build(set, options);
    EXPECT_TRUE(built) << built.error().message;
    return built ? std::move(built).value() : BuildResult{};
  }
  static double volumeError(const BuildResult& b, int f) {
    const MeshStats s = computeMeshStats(b.surfaces.mesh.positions, b.surfaces.features[static_cast<std::size_t>(f)].triangles);
    const double contour = b.overlaps.features[static_cast<std::size_t>(f)].contour;
    return (s.volume - contour) / contour;
  }
};

// At 0.25 mm pixels (8 layers per gap): within 3 % for one and two planes, 1 % for three.
TEST_F(InterpolationVolumeTest, FewPlaneStructuresKeepTheirSlabVolume) {
  const ContourSet set = smallStructures();
  for (double pixel : {0.25, 0.5}) {
    const BuildResult b = build(set, pixel);
    ASSERT_TRUE(b.interpolation.used());
    std::printf("[ figure   ] %.2f mm pixels, 2 mm planes:", pixel);
    for (std::size_t f = 0; f < set.features.size(); ++f) {
      const double e = volumeError(b, static_cast<int>(f));
      std::printf(" %s %+.1f %%", set.features[f].name.c_str(), 100 * e);
      const MeshStats s = computeMeshStats(b.surfaces.mesh.positions, b.surfaces.features[f].triangles);
      EXPECT_TRUE(s.closed && s.manifold && s.oriented) << set.features[f].name;
      EXPECT_EQ(s.components, 1) << set.features[f].name;
      if (pixel == 0.25) {
        const std::size_t planes = set.features[f].slices.size();
        EXPECT_LE(std::abs(e), planes >= 3 ? 0.01 : 0.03) << set.features[f].name << " at " << pixel << " mm";
      } else {
        // 4 layers per gap: the domes are coarse (one plane: -6.6 %, 69 % lost before them).
        EXPECT_LE(std::abs(e), 0.08) << set.features[f].name << " at " << pixel << " mm";
      }
    }
    std::printf("\n");
  }
}

}  // namespace
}  // namespace scansurf::test

namespace scansurf::test {
namespace {

// A feature drawn on planes 0, 4, 8 beside one drawn on 2 and 6: on the other's planes each
// holds its own slab (the nearer of its planes), so neither is cut into one piece per plane
// (A was three pieces holding half its volume), with interpolation on and off.
TEST_F(InterpolationVolumeTest, FeaturesOnInterleavedPlanesStayWhole) {
  ContourSet set;
  set.source = "interleaved";
  set.features = {onPlanes("A", circleContour({0, 0}, 10), {0, 4, 8}), onPlanes("B", circleContour({30, 0}, 8), {2, 6})};
  for (int factor : {1, InterpolationOptions::kAuto}) {
    SCOPED_TRACE(factor == 1 ? "interpolation off" : "interpolation auto");
    const BuildResult b = build(set, 0.5, factor);
    for (int f = 0; f < 2; ++f) {
      const MeshStats s = computeMeshStats(b.surfaces.mesh.positions, b.surfaces.features[static_cast<std::size_t>(f)].triangles);
      EXPECT_EQ(s.components, 1) << set.features[static_cast<std::size_t>(f)].name;
      EXPECT_LE(std::abs(volumeError(b, f)), 0.02) << set.features[static_cast<std::size_t>(f)].name;  // -50 % before
    }
    // Layer 2 (z = 2, B's plane) holds A's slab from its plane at z = 0: A is there in the labels.
    if (factor == 1) {
      const int k = layerOfZ(b.volume.grid, 2.0, 1e-6);
      ASSERT_GE(k, 0);
      std::size_t inA = 0;
      for (int j = 0; j < b.volume.grid.ny; ++j)
        for (int i = 0; i < b.volume.grid.nx; ++i) inA += b.volume.at(i, j, k) == labelOfFeature(0);
      EXPECT_GT(inA, 1000u);
    }
  }
}

}  // namespace
}  // namespace scansurf::test
