// Structures that overlap by design (issue 9): layered partitions keep every feature's own
// region; the single partition reports exactly what each feature lost.
#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "geometry/overlaps/overlap_analysis.h"
#include "gpu/gpu_test_env.h"
#include "support/intersections.h"
#include "support/shapes.h"

namespace scansurf::test {
namespace {

Feature circleFeature(const std::string& name, Point2 centre, double radius, int slices, double spacing = 2.0) {
  Feature f{name, {}, {}};
  for (int k = 0; k < slices; ++k) f.slices.push_back({k * spacing, {circleContour(centre, radius)}});
  return f;
}

// A half disc of the circle (x <= split when left), the straight side shared with its twin;
// split between pixel centres, as real boundaries are (a boundary through a column of centres
// gives that column to one side).
Feature halfDiscFeature(const std::string& name, double radius, bool left, int slices, double split = 0.25) {
  Feature f{name, {}, {}};
  for (int k = 0; k < slices; ++k) {
    Contour c;
    for (int i = 0; i <= 32; ++i) {
      const double a = -M_PI / 2 + M_PI * i / 32.0;
      c.points.push_back({split + (left ? -1 : 1) * radius * std::cos(a), radius * std::sin(a)});
    }
    f.slices.push_back({k * 2.0, {c}});
  }
  return f;
}

// BODY holding an organ, a margin partly over the organ, a skin mark half outside BODY.
std::vector<Feature> mixedFeatures() {
  return {circleFeature("BODY", {0, 0}, 30, 8), circleFeature("organ", {0, 0}, 10, 8), circleFeature("margin", {8, 0}, 6, 8),
          circleFeature("mark", {30, 0}, 3, 8)};
}

class OverlapsTest : public EngineTest {
 protected:
  static BuildResult build(const ContourSet& set, OverlapMode mode, double voxelSize = 0.5) {
    BuildOptions options;
    options.grid.voxelSize = voxelSize;
    options.overlaps = mode;
    options.smoothing.enabled = true;  // the CLI's default: cross-sections follow the contours
    auto built = engine_->build(set, options);
    EXPECT_TRUE(built) << built.error().message;
    return built ? std::move(built).value() : BuildResult{};
  }
  static MeshStats stats(const BuildResult& b, int f) {
    return computeMeshStats(b.surfaces.mesh.positions, b.surfaces.features[static_cast<std::size_t>(f)].triangles);
  }
  // Every feature: closed, oriented, and its surface volume within 1 % of its contour volume.
  static void expectOwnVolumes(const ContourSet& set, const BuildResult& b) {
    for (std::size_t f = 0; f < set.features.size(); ++f) {
      SCOPED_TRACE(set.features[f].name);
      const MeshStats s = stats(b, static_cast<int>(f));
      EXPECT_TRUE(s.closed && s.manifold && s.oriented);
      const double contour = b.overlaps.features[f].contour;
      EXPECT_NEAR(s.volume, contour, 0.01 * contour);
      // Pixel-centre sampling: a boundary through a row or column of centres moves it by one
      // pixel (a circle centred on a centre has whole rings of centres on its boundary).
      EXPECT_NEAR(b.overlaps.features[f].ownVolume, contour, 0.06 * contour);
    }
  }
};

TEST_F(OverlapsTest, TwoPartlyOverlappingFeaturesKeepTheirVolumesInTwoLayers) {
  ContourSet set;
  set.source = "two";
  set.features = {circleFeature("A", {0, 0}, 10, 8), circleFeature("B", {8, 0}, 10, 8)};
  const BuildResult b = build(set, OverlapMode::Layers);
  EXPECT_EQ(b.overlaps.layers, 2);
  ASSERT_EQ(b.overlaps.partialOverlaps().size(), 1u);
  EXPECT_GT(b.overlaps.partialOverlaps()[0].volume, 0.0);
  EXPECT_NE(b.overlaps.features[0].layer, b.overlaps.features[1].layer);
  expectOwnVolumes(set, b);
}

TEST_F(OverlapsTest, AChainOfOverlapsNeedsTwoLayers) {
  ContourSet set;
  set.source = "chain";
  set.features = {circleFeature("A", {0, 0}, 8, 6), circleFeature("B", {12, 0}, 8, 6), circleFeature("C", {24, 0}, 8, 6)};
  const BuildResult b = build(set, OverlapMode::Layers);
  EXPECT_EQ(b.overlaps.layers, 2);
  EXPECT_EQ(b.overlaps.partialOverlaps().size(), 2u);
  EXPECT_EQ(b.overlaps.features[0].layer, b.overlaps.features[2].layer) << "A and C do not overlap";
  expectOwnVolumes(set, b);
}

// A PTV over two abutting organs inside BODY: the organs stay in one layer and share their
// interface; the PTV keeps its full volume; nothing of one layer crosses.
TEST_F(OverlapsTest, PlanningVolumeOverTwoAbuttingOrgans) {
  ContourSet set;
  set.source = "ptv";
  set.features = {circleFeature("BODY", {0, 0}, 18, 8), halfDiscFeature("left", 12, true, 8),
                  halfDiscFeature("right", 12, false, 8), circleFeature("PTV", {8, 0}, 7, 8)};
  const BuildResult b = build(set, OverlapMode::Layers, 0.5);
  const OverlapReport& r = b.overlaps;
  EXPECT_EQ(r.layers, 2);
  EXPECT_EQ(r.features[1].layer, r.features[2].layer);
  EXPECT_EQ(r.features[0].layer, r.features[1].layer) << "BODY holds them: kept together";
  EXPECT_NE(r.features[3].layer, r.features[2].layer);
  expectOwnVolumes(set, b);
  // The organs share every interface vertex.
  const auto vertices = [&](int f) {
    return std::set<std::uint32_t>(b.surfaces.features[static_cast<std::size_t>(f)].triangles.begin(),
                                   b.surfaces.features[static_cast<std::size_t>(f)].triangles.end());
  };
  const std::set<std::uint32_t> left = vertices(1), right = vertices(2);
  std::size_t shared = 0;
  for (std::uint32_t v : left) shared += right.count(v);
  EXPECT_GT(shared, 100u);
  // Layer 0's surfaces (BODY, left, right) never cross one another (each shared interface
  // triangle once).
  std::set<std::array<std::uint32_t, 3>> seen;
  std::vector<std::uint32_t> layer0;
  for (int f : {0, 1, 2}) {
    const std::vector<std::uint32_t>& t = b.surfaces.features[static_cast<std::size_t>(f)].triangles;
    for (std::size_t i = 0; i < t.size(); i += 3) {
      std::array<std::uint32_t, 3> key{t[i], t[i + 1], t[i + 2]};
      std::sort(key.begin(), key.end());
      if (seen.insert(key).second) layer0.insert(layer0.end(), {t[i], t[i + 1], t[i + 2]});
    }
  }
  const IntersectionReport crossings = findCrossings(b.surfaces.mesh.positions, layer0);
  EXPECT_EQ(crossings.crossings, 0u);
  EXPECT_GT(crossings.pairsTested, 1000u);
}

// Nested and overlapping at once, and a skin mark partly outside BODY.
TEST_F(OverlapsTest, NestedPlusOverlappingAndAMarkOutsideTheBody) {
  ContourSet set;
  set.source = "mixed";
  set.features = mixedFeatures();
  const BuildResult b = build(set, OverlapMode::Layers);
  const OverlapReport& r = b.overlaps;
  EXPECT_EQ(r.partialOverlaps().size(), 2u) << "organ-margin and BODY-mark";
  EXPECT_EQ(r.layers, 2);
  EXPECT_GE(r.maskLayers, 2);
  for (const SharedVolume& s : r.shared)
    if (s.a == 0 && s.b == 1) {
      EXPECT_TRUE(s.nested);
    }
  expectOwnVolumes(set, b);
}

// The single partition: each feature's loss is exactly its own voxels minus its labelled ones.
TEST_F(OverlapsTest, PartitionReportsExactlyWhatEachFeatureLost) {
  ContourSet set;
  set.source = "partition";
  set.features = mixedFeatures();
  const BuildResult b = build(set, OverlapMode::Partition);
  EXPECT_EQ(b.overlaps.layers, 1);
  for (std::size_t f = 0; f < set.features.size(); ++f) {
    std::size_t labelled = 0, lost = 0;
    for (Label l : b.volume.labels) labelled += l == labelOfFeature(static_cast<int>(f));
    for (const VolumeLoss& loss : b.overlaps.losses)
      if (loss.feature == static_cast<int>(f)) lost += loss.voxels;
    SCOPED_TRACE(set.features[f].name);
    EXPECT_EQ(b.overlaps.features[f].ownVoxels - labelled, lost);
  }
  bool warned = false;
  for (const std::string& w : b.warnings) warned = warned || w.find("\"margin\" lost") != std::string::npos;
  EXPECT_TRUE(warned) << "the margin loses its overlap with the organ, which has priority";
}

// Nothing overlaps: layers mode gives exactly what the partition gives.
TEST_F(OverlapsTest, WithoutOverlapsLayersEqualThePartition) {
  const ContourSet set = phantomContours();
  const BuildResult layers = build(set, OverlapMode::Layers, 2.0), partition = build(set, OverlapMode::Partition, 2.0);
  EXPECT_EQ(layers.overlaps.layers, 1);
  EXPECT_EQ(layers.surfaces.mesh.positions, partition.surfaces.mesh.positions);
  EXPECT_EQ(layers.surfaces.mesh.triangles, partition.surfaces.mesh.triangles);
}

// Issue 15: every pair of 1500 features conflicts (a complete graph, as thousands of nested
// rings give the mask layers): DSatur colours it with 1500 distinct layers in one pass (it
// spent minutes on saturation recounts before), and a chain with affinity stays in one layer.
TEST(AssignLayers, CompleteGraphOfFifteenHundred) {
  constexpr int kN = 1500;
  std::vector<std::pair<int, int>> all, chain;
  for (int a = 0; a < kN; ++a) {
    for (int b = a + 1; b < kN; ++b) all.emplace_back(a, b);
    if (a + 1 < kN) chain.emplace_back(a, a + 1);
  }
  std::vector<int> layers = assignLayers(kN, all, chain);
  std::sort(layers.begin(), layers.end());
  for (int i = 0; i < kN; ++i) ASSERT_EQ(layers[static_cast<std::size_t>(i)], i);
  const std::vector<int> together = assignLayers(kN, {}, chain);
  EXPECT_TRUE(std::all_of(together.begin(), together.end(), [](int l) { return l == 0; }));
}

// Issue 12, item 3: without BuildOptions::keepLabelVolume the labels go from scan conversion
// to classification on the device; the surfaces are exactly those of the host round trip, in
// one partition and in layers, and the partition mode still has its labels for the losses.
TEST_F(OverlapsTest, LabelsLeftOnTheDeviceGiveTheSameSurfaces) {
  ContourSet set;
  set.source = "mixed";
  set.features = mixedFeatures();
  for (OverlapMode mode : {OverlapMode::Layers, OverlapMode::Partition}) {
    for (std::size_t count : {std::size_t{2}, set.features.size()}) {  // BODY and organ: one layer
      SCOPED_TRACE(std::to_string(count) + (mode == OverlapMode::Layers ? " features, layers" : " features, partition"));
      ContourSet part = set;
      part.features.resize(count);
      BuildOptions options;
      options.grid.voxelSize = 0.5;
      options.overlaps = mode;
      options.smoothing.enabled = true;
      auto kept = engine_->build(part, options);
      options.keepLabelVolume = false;
      auto onDevice = engine_->build(part, options);
      ASSERT_TRUE(kept && onDevice);
      EXPECT_EQ(onDevice->surfaces.mesh.positions, kept->surfaces.mesh.positions);
      EXPECT_EQ(onDevice->surfaces.mesh.triangles, kept->surfaces.mesh.triangles);
      EXPECT_EQ(onDevice->surfaces.mesh.labels, kept->surfaces.mesh.labels);
      for (std::size_t f = 0; f < count; ++f)
        EXPECT_EQ(onDevice->surfaces.features[f].triangles, kept->surfaces.features[f].triangles);
      EXPECT_EQ(onDevice->volume.grid.nx, kept->volume.grid.nx);
      EXPECT_EQ(kept->volume.labels.size(), kept->volume.grid.voxelCount());
      if (mode == OverlapMode::Partition) {
        EXPECT_EQ(onDevice->volume.labels, kept->volume.labels);  // the losses need them
        ASSERT_EQ(onDevice->overlaps.losses.size(), kept->overlaps.losses.size());
      } else {
        EXPECT_TRUE(onDevice->volume.labels.empty());
      }
      EXPECT_GT(kept->surfaces.mesh.triangleCount(), 0u);
    }
  }
}

}  // namespace
}  // namespace scansurf::test
