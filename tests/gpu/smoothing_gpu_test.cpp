// Smoothing inside Engine::build (issue 3): the "smoothing" stage runs when enabled, moves the
// vertices but not the triangles, keeps every surface closed and crossing-free, and agrees
// with smoothing the unsmoothed build's mesh on the CPU.
#include <algorithm>

#include "geometry/shape/triangle_shape.h"
#include "geometry/shape/volume_restoration.h"
#include "geometry/smoothing/smooth_mesh.h"
#include "gpu/gpu_test_env.h"
#include "support/intersections.h"
#include "support/shapes.h"

namespace scansurf::test {
namespace {

class SmoothingBuildTest : public GpuTest {};

TEST_F(SmoothingBuildTest, BuildSmoothsAbuttingHalvesWithoutCrossings) {
  auto engine = Engine::create(validatedEngineOptions());
  ASSERT_TRUE(engine) << engine.error().message;
  const ContourSet set = abuttingContours(10, 6, 2.5);
  BuildOptions options;
  options.grid.voxelSize = 0.5;
  auto raw = engine->build(set, options);
  ASSERT_TRUE(raw) << raw.error().message;
  options.smoothing.enabled = true;
  auto smooth = engine->build(set, options);
  ASSERT_TRUE(smooth) << smooth.error().message;

  const auto hasStage = [](const BuildResult& b) {
    return std::any_of(b.timings.begin(), b.timings.end(), [](const StageTime& t) { return t.stage == "smoothing"; });
  };
  EXPECT_FALSE(hasStage(*raw));
  EXPECT_TRUE(hasStage(*smooth));
  const MultiLabelMesh& a = raw->surfaces.mesh;
  const MultiLabelMesh& b = smooth->surfaces.mesh;
  EXPECT_LT(b.triangleCount(), a.triangleCount()) << "vertices crowding voxel centres merged into them";
  EXPECT_NE(a.positions, b.positions);

  // The engine smooths exactly as the CPU functions do on the raw mesh: relaxation, snapping,
  // the quads' diagonals, the cubes' fans, then each feature's volume restored to its slab volume
  // (the vertices placed between two of its planes moved last).
  MultiLabelMesh expected = a;
  const Grid& grid = raw->volume.grid;
  SmoothingReport relaxed = smoothMesh(expected, grid, &set, options.smoothing);
  const ShapedTriangles shaped = shapeTriangles(expected, grid, options.smoothing.snap, relaxed.onSheet);
  const TriangleShapeReport& snapped = shaped.report;
  EXPECT_GT(snapped.points, 0u);
  EXPECT_GT(snapped.quadsFlipped, 0u);
  EXPECT_GT(snapped.cubeFans, 0u);
  EXPECT_FALSE(raw->surfaces.triangleShape.ran);
  EXPECT_TRUE(smooth->surfaces.triangleShape.ran);
  EXPECT_EQ(smooth->surfaces.triangleShape.points, snapped.points);
  EXPECT_EQ(smooth->surfaces.triangleShape.removedTriangles, snapped.removedTriangles);
  EXPECT_EQ(smooth->surfaces.triangleShape.cubeFans, snapped.cubeFans);
  EXPECT_EQ(smooth->surfaces.triangleShape.fanVerticesRemoved, snapped.fanVerticesRemoved);
  EXPECT_EQ(a.triangleCount() - snapped.removedTriangles - 2 * snapped.fanVerticesRemoved, b.triangleCount());
  std::vector<double> targets;
  for (const FeatureVolumes& f : raw->overlaps.features) targets.push_back(f.contour);
  std::vector<bool> contourLayers(static_cast<std::size_t>(grid.nz), false);
  for (const Feature& f : set.features)
    for (const FeatureSlice& s : f.slices) contourLayers[static_cast<std::size_t>(grid.layerOfPlane(s.z))] = true;
  restoreVolumes(expected, grid, raw->nesting, targets, relaxed.onSheet, contourLayers, options.smoothing.minAngle, 0,
                 &shaped.disks, relaxed.betweenPlanes);
  EXPECT_EQ(expected.positions, b.positions);
  EXPECT_EQ(expected.triangles, b.triangles);
  EXPECT_EQ(expected.labels, b.labels);
  EXPECT_EQ(expected.keys, b.keys);

  for (const FeatureSurface& f : smooth->surfaces.features) {
    const MeshStats s = computeMeshStats(b.positions, f.triangles);
    EXPECT_TRUE(s.closed && s.manifold && s.oriented);
    EXPECT_EQ(s.genus, 0);
  }
  EXPECT_EQ(findCrossings(b.positions, b.triangles).crossings, 0u);
}

}  // namespace
}  // namespace scansurf::test
