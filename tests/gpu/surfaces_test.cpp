// The whole method on generated shapes: every feature surface a closed, consistently
// oriented 2-manifold with the right genus and components; volumes near analytic; abutting
// features sharing their interface.
#include <algorithm>
#include <cmath>
#include <set>

#include "geometry/contours/validate.h"
#include "gpu/gpu_test_env.h"
#include "io/contours_json.h"
#include "scansurf/input.h"
#include "support/shapes.h"
#include "support/surface_checks.h"

namespace scansurf::test {
namespace {

class SurfacesTest : public EngineTest {
 protected:
  static BuildResult build(const ContourSet& set, double voxelSize, SurfaceConvention convention = SurfaceConvention::Enclosing) {
    BuildOptions options;
    options.grid.voxelSize = voxelSize;
    options.convention = convention;
    auto built = engine_->build(set, options);
    EXPECT_TRUE(built) << built.error().message;
    return built ? std::move(built).value() : BuildResult{};
  }
  static MeshStats stats(const BuildResult& b, int feature) {
    return computeMeshStats(b.surfaces.mesh.positions, b.surfaces.features[static_cast<std::size_t>(feature)].triangles);
  }
  static void expectClosedManifold(const BuildResult& b) {
    for (std::size_t f = 0; f < b.surfaces.features.size(); ++f) {
      const MeshStats s = stats(b, static_cast<int>(f));
      SCOPED_TRACE("feature " + std::to_string(f));
      EXPECT_GT(s.triangles, 0u);
      EXPECT_TRUE(s.closed);
      EXPECT_TRUE(s.manifold);
      EXPECT_TRUE(s.oriented);
      EXPECT_GT(s.volume, 0.0) << "outward orientation";
    }
  }
  static std::set<std::uint32_t> vertices(const std::vector<std::uint32_t>& triangles) {
    return {triangles.begin(), triangles.end()};
  }
};

TEST_F(SurfacesTest, SphereIsClosedGenusZeroWithinThreePercentOfAnalyticVolume) {
  const double r = 10;
  const BuildResult b = build(sphereContours(r, 1.0), 1.0);
  expectClosedManifold(b);
  const MeshStats s = stats(b, 0);
  EXPECT_EQ(s.genus, 0);
  EXPECT_EQ(s.components, 1);
  const double analytic = 4.0 / 3.0 * M_PI * r * r * r;
  const double error = std::abs(s.volume - analytic) / analytic;
  RecordProperty("sphere_volume_error_percent", std::to_string(100 * error));
  std::printf("[ figures  ] 20 mm sphere at 1 mm: %zu triangles, volume %.1f mm3 (analytic %.1f, error %.2f %%)\n", s.triangles,
              s.volume, analytic, 100 * error);
  EXPECT_LT(error, 0.03);
  EXPECT_TRUE(b.warnings.empty());
}

TEST_F(SurfacesTest, TorusHasGenusOne) {
  const BuildResult b = build(torusContours(10, 4, 1.0), 0.5);
  expectClosedManifold(b);
  const MeshStats s = stats(b, 0);
  EXPECT_EQ(s.genus, 1);
  EXPECT_EQ(s.components, 1);
  const double analytic = 2 * M_PI * M_PI * 10 * 4 * 4;
  std::printf("[ figures  ] torus R10 r4 at 0.5 mm: volume %.1f mm3 (analytic %.1f, error %.2f %%)\n", s.volume, analytic,
              100 * std::abs(s.volume - analytic) / analytic);
  EXPECT_LT(std::abs(s.volume - analytic) / analytic, 0.03);
}

TEST_F(SurfacesTest, YBranchIsOneGenusZeroSurface) {
  const BuildResult b = build(yBranchContours(), 0.5);
  expectClosedManifold(b);
  const MeshStats s = stats(b, 0);
  EXPECT_EQ(s.genus, 0);
  EXPECT_EQ(s.components, 1);
}

TEST_F(SurfacesTest, NestedSpheresEnclosingAndPartitionConventions) {
  const ContourSet set = nestedSpheresContours(20, 8, 2.5);
  const BuildResult enclosing = build(set, 1.0, SurfaceConvention::Enclosing);
  const BuildResult partition = build(set, 1.0, SurfaceConvention::Partition);
  expectClosedManifold(enclosing);
  ASSERT_EQ(enclosing.nesting.order.front(), 1) << "inner first";
  const MeshStats outerEnclosing = stats(enclosing, 0), inner = stats(enclosing, 1);
  const MeshStats outerPartition = stats(partition, 0);
  EXPECT_EQ(outerEnclosing.components, 1) << "a closed skin, not a shell";
  EXPECT_EQ(outerPartition.components, 2) << "a shell: outside and the cavity";
  EXPECT_TRUE(outerPartition.closed && outerPartition.manifold && outerPartition.oriented);
  EXPECT_NEAR(outerPartition.volume, outerEnclosing.volume - inner.volume, 1e-6 * outerEnclosing.volume);
  // The cavity of the partition surface is the inner sphere's surface, vertex for vertex.
  const auto innerVertices = vertices(enclosing.surfaces.features[1].triangles);
  const auto shellVertices = vertices(partition.surfaces.features[0].triangles);
  for (std::uint32_t v : innerVertices) ASSERT_TRUE(shellVertices.count(v));
}

TEST_F(SurfacesTest, AbuttingFeaturesShareEveryInterfaceVertex) {
  const BuildResult b = build(abuttingContours(10, 6, 2.5), 0.5);
  expectClosedManifold(b);
  const auto& mesh = b.surfaces.mesh;
  const InterfaceUse use =
      interfaceUse(mesh, b.surfaces.features[0], b.surfaces.features[1], labelOfFeature(0), labelOfFeature(1));
  ASSERT_EQ(use.unshared, 0u) << "interface vertices missing from a surface";
  EXPECT_GT(use.triangles, 50u);
  // No gap, no overlap: the interface triangles are shared with opposite orientations, so the
  // two volumes add up exactly to the volume inside the union's outer boundary (the
  // triangles between background and either feature, whose normals point into the feature).
  std::vector<std::uint32_t> outer;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    if (mesh.labels[2 * t] == kBackground)
      outer.insert(outer.end(), {mesh.triangles[3 * t], mesh.triangles[3 * t + 2], mesh.triangles[3 * t + 1]});
  const MeshStats unionStats = computeMeshStats(mesh.positions, outer);
  EXPECT_TRUE(unionStats.closed && unionStats.manifold && unionStats.oriented);
  const double sum = stats(b, 0).volume + stats(b, 1).volume;
  EXPECT_NEAR(sum, unionStats.volume, 1e-9 * unionStats.volume);
}

// The stages one by one (nesting, grid, scanConvert, extract) give exactly what build()
// gives, smoothing included.
TEST_F(SurfacesTest, StageByStageEqualsBuild) {
  const ContourSet set = nestedSpheresContours(12, 5, 2.0);
  BuildOptions options;
  options.grid.voxelSize = 1.0;
  options.convention = SurfaceConvention::Partition;
  options.smoothing.enabled = true;
  options.smoothing.iterations = 20;
  auto built = engine_->build(set, options);
  ASSERT_TRUE(built) << built.error().message;
  const Nesting nesting = computeNesting(set, options.grid.sliceTolerance);
  auto grid = makeGrid(set, options.grid);
  ASSERT_TRUE(grid) << grid.error().message;
  auto volume = engine_->scanConvert(set, nesting, *grid, options);
  ASSERT_TRUE(volume) << volume.error().message;
  EXPECT_EQ(volume->labels, built->volume.labels);
  auto surfaces = engine_->extract(*volume, nesting, options, &set);
  ASSERT_TRUE(surfaces) << surfaces.error().message;
  EXPECT_EQ(surfaces->mesh.positions, built->surfaces.mesh.positions);
  EXPECT_EQ(surfaces->mesh.triangles, built->surfaces.mesh.triangles);
  EXPECT_EQ(surfaces->mesh.labels, built->surfaces.mesh.labels);
  ASSERT_EQ(surfaces->features.size(), built->surfaces.features.size());
  for (std::size_t f = 0; f < surfaces->features.size(); ++f)
    EXPECT_EQ(surfaces->features[f].triangles, built->surfaces.features[f].triangles);
  // Smoothing ran in both: the positions left the half-voxel lattice.
  auto raw = engine_->extract(*volume, nesting, BuildOptions{options.grid, options.convention}, &set);
  ASSERT_TRUE(raw) << raw.error().message;
  EXPECT_NE(raw->mesh.positions, surfaces->mesh.positions);
}

// GridOptions::sliceTolerance reaches nesting and scan conversion, not only the grid: two
// features drawn 0.05 apart with a tolerance of 0.1 are on one plane (issue 13's regression).
TEST_F(SurfacesTest, SliceToleranceReachesEveryStage) {
  ContourSet set = sphereContours(5, 1.0);
  Feature b = set.features[0];
  b.name = "b";
  for (FeatureSlice& slice : b.slices) {
    slice.z += 0.05;
    for (Contour& c : slice.contours)
      for (Point2& p : c.points) p.x += 20;  // beside the sphere
  }
  set.features.push_back(b);
  BuildOptions options;
  options.grid.voxelSize = 0.5;
  options.grid.sliceTolerance = 0.1;
  auto built = engine_->build(set, options);
  ASSERT_TRUE(built) << built.error().message;
  const MeshStats a = stats(*built, 0), moved = stats(*built, 1);
  EXPECT_TRUE(moved.closed && moved.manifold && moved.oriented);
  EXPECT_NEAR(moved.volume, a.volume, 1e-6 * a.volume) << "both spheres on the same layers";
}

// The plane tolerance follows the data's own slice spacing, not its unit: the same sphere in
// millimetres and scaled to 2 nm sections in metres gives the same surface, scaled (a fixed
// 0.001-unit tolerance merged every nm section into one plane and gave an empty surface).
TEST_F(SurfacesTest, SliceToleranceFollowsTheSpacingInAnyUnit) {
  auto scaled = [](double factor, const char* units) {
    ContourSet set = sphereContours(5, 2.0);
    set.units = units;
    for (FeatureSlice& slice : set.features[0].slices) {
      slice.z *= factor;
      for (Contour& c : slice.contours)
        for (Point2& p : c.points) p.x *= factor, p.y *= factor;
    }
    EXPECT_TRUE(validateAndNormalize(set));
    return set;
  };
  const ContourSet mm = scaled(1, "mm"), nm = scaled(1e-9, "m");
  EXPECT_EQ(nm.features[0].slices.size(), mm.features[0].slices.size());
  EXPECT_NEAR(nm.planeTolerance, 2e-12, 1e-20);
  auto a = engine_->build(mm, BuildOptions{});
  auto b = engine_->build(nm, BuildOptions{});
  ASSERT_TRUE(a && b);
  EXPECT_EQ(b->volume.grid.nz, a->volume.grid.nz);
  const MeshStats sa = stats(*a, 0), sb = stats(*b, 0);
  EXPECT_TRUE(sb.closed && sb.manifold);
  EXPECT_GT(sa.volume, 400);
  EXPECT_NEAR(sb.volume * 1e27, sa.volume, 1e-4 * sa.volume);
}

// Contours made in memory meet the same checks as a file's: build() validates a copy of a set
// that has not been validated (a bad contour is refused naming it; slices in any order give
// what the validated set gives), and validateContours is public for callers that validate first.
TEST_F(SurfacesTest, BuildValidatesContoursMadeInMemory) {
  ContourSet bad = sphereContours(5, 1.0);
  bad.source = "app";
  bad.features[0].slices[2].contours[0].points.resize(2);
  auto refused = engine_->build(bad, BuildOptions{});
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, Errc::InvalidInput);
  EXPECT_NE(refused.error().message.find("app: feature \"sphere\" (#0), slice z="), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("contour 0: fewer than 3 distinct points"), std::string::npos);

  ContourSet shuffled = sphereContours(5, 1.0);
  std::reverse(shuffled.features[0].slices.begin(), shuffled.features[0].slices.end());
  ContourSet validated = shuffled;
  ASSERT_TRUE(validateContours(validated));
  EXPECT_GT(validated.planeTolerance, 0);
  auto a = engine_->build(shuffled, BuildOptions{}), b = engine_->build(validated, BuildOptions{});
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->surfaces.mesh.positions, b->surfaces.mesh.positions);
  EXPECT_EQ(a->surfaces.mesh.triangles, b->surfaces.mesh.triangles);
}

// Progress: every stage begins and then ends once, in order, per surface layer, labelled with
// its layer when the build has several (two circles half over each other: two layers).
TEST_F(SurfacesTest, EveryStageBeginsAndEndsOncePerLayer) {
  ContourSet set = sphereContours(6, 1.0);
  Feature b = set.features[0];
  b.name = "half over";
  for (FeatureSlice& slice : b.slices)
    for (Contour& c : slice.contours)
      for (Point2& p : c.points) p.x += 6;
  set.features.push_back(b);
  BuildOptions options;
  options.grid.voxelSize = 0.5;
  options.smoothing.enabled = true;
  std::vector<BuildOptions::StageEvent> events;
  options.onStageEvent = [&](const BuildOptions::StageEvent& e) { events.push_back(e); };
  auto built = engine_->build(set, options);
  ASSERT_TRUE(built) << built.error().message;
  ASSERT_EQ(built->overlaps.layers, 2);
  ASSERT_EQ(events.size(), 2 * (4 + 2 * 6)) << "grid, nesting, overlap analysis, audit; per layer scan conversion, "
                                               "classification, assembly, smoothing, triangle shape, feature surfaces";
  std::vector<std::string> layered;
  for (std::size_t i = 0; i + 1 < events.size(); i += 2) {
    EXPECT_FALSE(events[i].done) << events[i].stage;
    EXPECT_TRUE(events[i + 1].done) << events[i + 1].stage;
    EXPECT_EQ(events[i].stage, events[i + 1].stage);
    EXPECT_EQ(events[i].layer, events[i + 1].layer);
    if (events[i].layer >= 0) {
      EXPECT_EQ(events[i].layers, 2);
      layered.push_back(std::to_string(events[i].layer) + " " + events[i].stage);
    }
  }
  EXPECT_EQ(layered.front(), "0 scan conversion");
  EXPECT_EQ(layered.back(), "1 feature surfaces");
  EXPECT_EQ(events.front().stage, "grid");
  EXPECT_EQ(events.back().stage, "audit");
}

// A feature left without a surface is reported by name, never dropped in silence.
TEST_F(SurfacesTest, FeaturesWithoutASurfaceAreReported) {
  ContourSet set = sphereContours(5, 1.0);
  set.features.push_back(set.features[0]);  // the same shape again: the first one wins it
  set.features[1].name = "twin";
  set.features.push_back({"empty", {}, {}});  // no slices at all
  const BuildResult partition = build(set, 0.5, SurfaceConvention::Partition);
  ASSERT_EQ(partition.surfaces.features.size(), 3u);
  EXPECT_GT(partition.surfaces.features[0].triangleCount(), 0u);
  EXPECT_EQ(partition.surfaces.features[1].triangleCount(), 0u);
  EXPECT_EQ(partition.surfaces.features[2].triangleCount(), 0u);
  auto mentions = [&](const std::string& name) {
    for (const std::string& w : partition.warnings)
      if (w.find("\"" + name + "\"") != std::string::npos && w.find("no surface") != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(mentions("twin"));
  EXPECT_TRUE(mentions("empty"));
  EXPECT_FALSE(mentions("sphere"));
}

TEST_F(SurfacesTest, BundledPhantomBuildsClosedSurfaces) {
  auto set = readContoursJson(SCANSURF_EXAMPLES "/phantom.json");
  ASSERT_TRUE(set) << set.error().message;
  for (SurfaceConvention c : {SurfaceConvention::Enclosing, SurfaceConvention::Partition}) {
    const BuildResult b = build(*set, 1.0, c);
    expectClosedManifold(b);
  }
}

// Every CPU stage splits its work by the thread count; none may let the count reach the result.
// The bundled phantom with the command-line tool's options (interpolated layers, round caps, smoothing, volume
// restoration, triangle shape, simplification), mesh and audit compared bit for bit.
TEST_F(SurfacesTest, TheWholeRunIsTheSameOnOneTwoAndThreeThreads) {
  auto set = readContoursJson(SCANSURF_EXAMPLES "/phantom.json");
  ASSERT_TRUE(set) << set.error().message;
  std::vector<BuildResult> runs;
  for (int threads : {1, 2, 3}) {
    BuildOptions options = BuildOptions::recommended();
    options.grid.voxelSize = 0.8;  // 3 layers a gap of 2.5 mm
    options.threads = threads;
    auto built = engine_->build(*set, options);
    ASSERT_TRUE(built) << built.error().message;
    ASSERT_EQ(built->threads, threads);
    runs.push_back(std::move(built).value());
  }
  ASSERT_GT(runs[0].interpolation.maxFactor, 1) << "the run must interpolate layers";
  for (std::size_t r = 1; r < runs.size(); ++r) {
    SCOPED_TRACE("threads " + std::to_string(runs[r].threads));
    const MultiLabelMesh &a = runs[0].surfaces.mesh, &b = runs[r].surfaces.mesh;
    EXPECT_TRUE(a.positions == b.positions);
    EXPECT_TRUE(a.triangles == b.triangles);
    EXPECT_TRUE(a.labels == b.labels);
    ASSERT_EQ(runs[0].surfaces.features.size(), runs[r].surfaces.features.size());
    for (std::size_t f = 0; f < runs[0].surfaces.features.size(); ++f)
      EXPECT_TRUE(runs[0].surfaces.features[f].triangles == runs[r].surfaces.features[f].triangles) << "feature " << f;
    EXPECT_EQ(runs[0].warnings, runs[r].warnings);
  }
}

// A 512 x 512 x 400 volume: scan conversion and classification in slabs, since its labels
// (210 MB) exceed lavapipe's 128 MiB maxStorageBufferRange.
TEST_F(SurfacesTest, Volume512x512x400WorksInSlabs) {
  const ContourSet set = sphereContours(100, 0.5);
  ASSERT_EQ(set.features[0].slices.size(), 400u);
  BuildOptions options;
  options.grid.nx = 512;
  options.grid.ny = 512;
  auto built = engine_->build(set, options);
  ASSERT_TRUE(built) << built.error().message;
  EXPECT_EQ(built->volume.grid.nz, 402);
  const MeshStats s = computeMeshStats(built->surfaces.mesh.positions, built->surfaces.features[0].triangles);
  EXPECT_TRUE(s.closed && s.manifold && s.oriented);
  EXPECT_EQ(s.genus, 0);
  const double analytic = 4.0 / 3.0 * M_PI * 100 * 100 * 100;
  EXPECT_LT(std::abs(s.volume - analytic) / analytic, 0.01);
  for (const StageTime& t : built->timings) std::printf("[ timing   ] %-18s %.2f s\n", t.stage.c_str(), t.seconds);
}

}  // namespace
}  // namespace scansurf::test
