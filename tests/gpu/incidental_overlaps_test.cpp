// Incidental overlaps (scansurf/overlaps.h, OverlapTolerance): hand-drawn neighbours overlap by
// slivers along their interface and must still share one surface; overlaps by design (a PTV,
// a deep poke) stay layers.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "geometry/overlaps/label_layers.h"
#include "geometry/overlaps/overlap_analysis.h"
#include "gpu/gpu_test_env.h"
#include "support/drawn_shapes.h"
#include "support/intersections.h"

namespace scansurf::test {
namespace {

int featureNamed(const ContourSet& set, const std::string& name) {
  for (std::size_t f = 0; f < set.features.size(); ++f)
    if (set.features[f].name == name) return static_cast<int>(f);
  return -1;
}

const SharedVolume* pairOf(const OverlapReport& r, int a, int b) {
  for (const SharedVolume& s : r.shared)
    if (s.a == std::min(a, b) && s.b == std::max(a, b)) return &s;
  return nullptr;
}

// Triangles of the mesh's layer holding feature f, each once (interfaces are shared).
std::vector<std::uint32_t> layerTriangles(const BuildResult& b, int layer) {
  std::set<std::array<std::uint32_t, 3>> seen;
  std::vector<std::uint32_t> out;
  for (std::size_t f = 0; f < b.surfaces.features.size(); ++f) {
    if (b.overlaps.features[f].layer != layer) continue;
    const std::vector<std::uint32_t>& t = b.surfaces.features[f].triangles;
    for (std::size_t i = 0; i < t.size(); i += 3) {
      std::array<std::uint32_t, 3> key{t[i], t[i + 1], t[i + 2]};
      std::sort(key.begin(), key.end());
      if (seen.insert(key).second) out.insert(out.end(), {t[i], t[i + 1], t[i + 2]});
    }
  }
  return out;
}

// Triangles between the two features (their shared interface).
std::size_t interfaceTriangles(const BuildResult& b, int f, int g) {
  const Label lo = labelOfFeature(std::min(f, g)), hi = labelOfFeature(std::max(f, g));
  std::size_t n = 0;
  for (std::size_t t = 0; t < b.surfaces.mesh.triangleCount(); ++t)
    n += b.surfaces.mesh.labels[2 * t] == lo && b.surfaces.mesh.labels[2 * t + 1] == hi;
  return n;
}

class IncidentalOverlapsTest : public EngineTest {
 protected:
  // The CLI's smoothing; interpolation off and flat caps keep the volume checks about overlaps.
  static BuildOptions options(double voxelSize) {
    BuildOptions o;
    o.grid.voxelSize = voxelSize;  // 0: the default grid
    o.smoothing.enabled = true;
    o.interpolation.caps = CapShape::Flat;
    return o;
  }
  static BuildResult build(const ContourSet& set, const BuildOptions& o) {
    auto built = engine_->build(set, o);
    EXPECT_TRUE(built) << built.error().message;
    return built ? std::move(built).value() : BuildResult{};
  }
  static MeshStats stats(const BuildResult& b, int f) {
    return computeMeshStats(b.surfaces.mesh.positions, b.surfaces.features[static_cast<std::size_t>(f)].triangles);
  }
  // One layer, no crossing, a shared interface, each surface within 1 % of its contour volume,
  // and each side's given-up volume adding up to the shared volume.
  static void expectSharedInterface(const ContourSet& set, const BuildResult& b, int f, int g, double volumeTolerance = 0.01,
                                    bool thin = true) {
    SCOPED_TRACE(set.features[static_cast<std::size_t>(f)].name + " | " + set.features[static_cast<std::size_t>(g)].name);
    const SharedVolume* s = pairOf(b.overlaps, f, g);
    ASSERT_NE(s, nullptr) << "drawn independently, they overlap somewhere";
    EXPECT_TRUE(s->incidental);
    EXPECT_EQ(s->depthMeasured, thin);
    EXPECT_EQ(b.overlaps.features[static_cast<std::size_t>(f)].layer, b.overlaps.features[static_cast<std::size_t>(g)].layer);
    EXPECT_GT(interfaceTriangles(b, f, g), 100u);
    for (int h : {f, g}) {
      const MeshStats m = stats(b, h);
      const double contour = b.overlaps.features[static_cast<std::size_t>(h)].contour;
      EXPECT_TRUE(m.closed && m.manifold && m.oriented);
      EXPECT_NEAR(m.volume, contour, volumeTolerance * contour) << set.features[static_cast<std::size_t>(h)].name;
    }
  }
  static void expectNoCrossings(const BuildResult& b, int layer) {
    const IntersectionReport crossings = findCrossings(b.surfaces.mesh.positions, layerTriangles(b, layer));
    EXPECT_EQ(crossings.crossings, 0u);
    EXPECT_GT(crossings.pairsTested, 1000u);
  }
};

// Prostate and rectum drawn independently, at 1 mm pixels, pixels equal to the 2 mm planes and
// the default grid: one layer, one interface, nothing crossing.
TEST_F(IncidentalOverlapsTest, IndependentlyDrawnNeighboursShareOneSurface) {
  const ContourSet set = drawnPelvisContours();
  const int prostate = featureNamed(set, "prostate"), rectum = featureNamed(set, "rectum");
  for (double voxel : {1.0, 2.0, 0.0}) {
    SCOPED_TRACE("voxel size " + std::to_string(voxel));
    const BuildResult b = build(set, options(voxel));
    EXPECT_EQ(b.overlaps.layers, 1);
    // 2 mm pixels: smoothing alone loses 1.1 % of the prostate (the rule off too); the split
    // must cost no more than the sliver it gives up.
    expectSharedInterface(set, b, prostate, rectum, voxel == 2.0 ? 0.015 : 0.01);
    expectNoCrossings(b, 0);
    const SharedVolume* s = pairOf(b.overlaps, prostate, rectum);
    EXPECT_NEAR(s->givenUpByA + s->givenUpByB, s->volume, 1e-9 * s->volume);
    EXPECT_GT(std::min(s->givenUpByA, s->givenUpByB), 0.0) << "a medial split, not a priority rule";
    BuildOptions off = options(voxel);
    off.overlapTolerance.enabled = false;
    const BuildResult layered = build(set, off);
    for (int f : {prostate, rectum}) {
      const double given = f == s->a ? s->givenUpByA : s->givenUpByB;
      EXPECT_GE(stats(b, f).volume,
                stats(layered, f).volume - given - 0.002 * b.overlaps.features[static_cast<std::size_t>(f)].contour);
    }
    // The figures docs/overlaps.md quotes: crossings between the two organs with the rule off
    // (their layers' meshes together) against none with it; each surface's volume error.
    std::vector<std::uint32_t> both = layerTriangles(layered, 0);
    const std::vector<std::uint32_t> second = layerTriangles(layered, 1);
    both.insert(both.end(), second.begin(), second.end());
    const std::size_t before = findCrossings(layered.surfaces.mesh.positions, both).crossings;
    EXPECT_GT(before, 0u) << "drawn independently, layered surfaces cross";
    const auto error = [&](const BuildResult& r, int f) {
      const double c = r.overlaps.features[static_cast<std::size_t>(f)].contour;
      return 100 * (stats(r, f).volume - c) / c;
    };
    std::printf(
        "pelvis at %s: pixels %.3g mm, shared %.1f mm3 (depth %.2f mm); crossings %zu -> 0; volume error prostate "
        "%+.2f -> %+.2f %%, rectum %+.2f -> %+.2f %%\n",
        voxel == 0 ? "the default grid" : (std::to_string(voxel).substr(0, 3) + " mm").c_str(), b.volume.grid.spacingX, s->volume,
        s->depth, before, error(layered, prostate), error(b, prostate), error(layered, rectum), error(b, rectum));
  }
}

// The rule off: every shared voxel means layers, as before.
TEST_F(IncidentalOverlapsTest, TheRuleOffGivesLayers) {
  const ContourSet set = drawnPelvisContours();
  BuildOptions o = options(1.0);
  o.overlapTolerance.enabled = false;
  const BuildResult b = build(set, o);
  EXPECT_EQ(b.overlaps.layers, 2);
  const SharedVolume* s = pairOf(b.overlaps, featureNamed(set, "prostate"), featureNamed(set, "rectum"));
  ASSERT_NE(s, nullptr);
  EXPECT_FALSE(s->incidental);
  EXPECT_EQ(s->givenUpByA + s->givenUpByB, 0.0);
}

// A 1.2 mm overlap along the whole 40 mm interface of two 80 x 40 mm rectangles (1.5 % of each): thin
// and small, so incidental; on the contour planes the shared surface runs on the medial line
// between the two outlines (x = -0.3 and x = +0.9: at 0.3), not on either.
TEST_F(IncidentalOverlapsTest, LongThinOverlapIsSplitDownItsMiddle) {
  ContourSet set = thinOverlapContours(1.2);
  for (Feature& f : set.features)
    for (FeatureSlice& s : f.slices)
      for (Point2& p : s.contours[0].points) p.x += 0.3;  // off the pixel centres: no ties
  const BuildResult b = build(set, options(1.0));
  EXPECT_EQ(b.overlaps.layers, 1);
  expectSharedInterface(set, b, 0, 1, 0.015);  // smoothing rounds the square corners: 1.1 %
  expectNoCrossings(b, 0);
  double sum = 0;
  std::size_t n = 0;
  const Label lo = labelOfFeature(0), hi = labelOfFeature(1);
  for (std::size_t t = 0; t < b.surfaces.mesh.triangleCount(); ++t) {
    if (b.surfaces.mesh.labels[2 * t] != lo || b.surfaces.mesh.labels[2 * t + 1] != hi) continue;
    for (int c = 0; c < 3; ++c) {
      const float* p = &b.surfaces.mesh.positions[3 * b.surfaces.mesh.triangles[3 * t + c]];
      // On a contour plane (z = 1, 3, ...), away from the junctions with the background.
      if (std::abs(p[1]) > 18 || std::abs(std::fmod(p[2] + 1, 2.0f)) > 1e-3f) continue;
      EXPECT_GE(p[0], -0.3f - 1e-3f);
      EXPECT_LE(p[0], 0.9f + 1e-3f);
      sum += p[0], ++n;
    }
  }
  ASSERT_GT(n, 0u);
  EXPECT_NEAR(sum / static_cast<double>(n), 0.3, 0.05) << "the interface's mean x on the planes: the medial line";
  const SharedVolume* s = pairOf(b.overlaps, 0, 1);
  // Voxel by voxel, the one shared column lies on the left's side of the medial line.
  EXPECT_EQ(s->givenUpByA, 0.0);
  EXPECT_EQ(s->givenUpByB, s->volume);
}

// The rectum poking 6 mm wide into the prostate on two planes, deeper than the limit from
// either outline. 5 mm deep, its region is tiny against both (under 1 % of the smaller):
// incidental whatever its depth, one layer, split medially. 12 mm deep it is not: real by its
// depth (small, under 2 %), and 20 mm deep real by its size too: two layers.
TEST_F(IncidentalOverlapsTest, ADeepPokeIsRealOnlyWhenNotTiny) {
  for (double poke : {5.0, 12.0, 20.0}) {
    DrawnPelvisOptions o;
    o.jitter = 0;
    o.pokeDepth = poke;
    const ContourSet set = drawnPelvisContours(o);
    const int prostate = featureNamed(set, "prostate"), rectum = featureNamed(set, "rectum");
    for (double voxel : {1.0, 0.5}) {
      SCOPED_TRACE("poke " + std::to_string(poke) + ", voxel size " + std::to_string(voxel));
      const BuildResult b = build(set, options(voxel));
      const SharedVolume* s = pairOf(b.overlaps, prostate, rectum);
      ASSERT_NE(s, nullptr);
      const double smaller = std::min(b.overlaps.features[static_cast<std::size_t>(prostate)].ownVolume,
                                      b.overlaps.features[static_cast<std::size_t>(rectum)].ownVolume);
      std::printf("[ figure   ] poke %.0f mm at %.1f mm pixels: %d region(s), the largest %.2f %% of the smaller, %s\n", poke,
                  voxel, s->regions, 100 * s->largestRegion / smaller, s->incidental ? "incidental" : "real");
      EXPECT_GE(s->regions, 1);
      EXPECT_LE(s->largestRegion, s->volume);
      EXPECT_FALSE(s->depthMeasured) << "deeper than the limit";
      const bool tiny = poke == 5.0;
      EXPECT_EQ(s->largestRegion < 0.01 * smaller, tiny);
      EXPECT_EQ(s->incidental, tiny);
      EXPECT_EQ(b.overlaps.layers, tiny ? 1 : 2);
      if (tiny) {
        expectSharedInterface(set, b, prostate, rectum, 0.015, false);
        expectNoCrossings(b, 0);
      }
    }
  }
}

// A PTV over both organs: its own layer at full volume, while the organs share their
// interface in theirs.
TEST_F(IncidentalOverlapsTest, PlanningVolumeOverTwoIndependentlyDrawnOrgans) {
  DrawnPelvisOptions o;
  o.planningVolume = true;
  const ContourSet set = drawnPelvisContours(o);
  const int prostate = featureNamed(set, "prostate"), rectum = featureNamed(set, "rectum"), ptv = featureNamed(set, "PTV");
  const BuildResult b = build(set, options(1.0));
  EXPECT_EQ(b.overlaps.layers, 2);
  EXPECT_FALSE(pairOf(b.overlaps, ptv, rectum)->incidental);
  EXPECT_NE(b.overlaps.features[static_cast<std::size_t>(ptv)].layer,
            b.overlaps.features[static_cast<std::size_t>(rectum)].layer);
  expectSharedInterface(set, b, prostate, rectum);
  expectNoCrossings(b, b.overlaps.features[static_cast<std::size_t>(prostate)].layer);
  const MeshStats m = stats(b, ptv);
  const double contour = b.overlaps.features[static_cast<std::size_t>(ptv)].contour;
  EXPECT_NEAR(m.volume, contour, 0.01 * contour) << "the PTV keeps its full volume";
}

// Three sectors meeting at a junction line, each drawn on its own: every pair incidental, one
// layer, three interfaces, no crossing.
TEST_F(IncidentalOverlapsTest, ThreeNeighboursMeetingAtAJunction) {
  const ContourSet set = drawnSectorsContours(0.5, 3);
  for (double voxel : {0.5, 0.0}) {
    SCOPED_TRACE("voxel size " + std::to_string(voxel));
    const BuildResult b = build(set, options(voxel));
    EXPECT_EQ(b.overlaps.layers, 1);
    for (auto [f, g] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 2}}) expectSharedInterface(set, b, f, g);
    expectNoCrossings(b, 0);
  }
}

// The split is for surfaces only: each feature's mask in the label volume files is its whole
// own region, overlap included, exactly as with the rule off.
TEST_F(IncidentalOverlapsTest, MasksKeepEachFeaturesOwnRegion) {
  const ContourSet set = drawnPelvisContours();
  BuildOptions on = options(1.0), off = on;
  off.overlapTolerance.enabled = false;
  const BuildResult a = build(set, on), b = build(set, off);
  const std::vector<FeatureRegion> regions = rasterizeFeatures(set, a.volume.grid, a.subPixelBits, 1);
  EXPECT_EQ(a.overlaps.maskLayers, b.overlaps.maskLayers);
  const std::vector<LabelVolume> masksA = maskLayerVolumes(regions, a.volume.grid, a.overlaps);
  const std::vector<LabelVolume> masksB = maskLayerVolumes(regions, b.volume.grid, b.overlaps);
  ASSERT_EQ(masksA.size(), masksB.size());
  for (std::size_t m = 0; m < masksA.size(); ++m) EXPECT_EQ(masksA[m].labels, masksB[m].labels);
  for (std::size_t f = 0; f < set.features.size(); ++f) {
    std::size_t voxels = 0;
    for (const LabelVolume& m : masksA)
      voxels += static_cast<std::size_t>(std::count(m.labels.begin(), m.labels.end(), labelOfFeature(static_cast<int>(f))));
    EXPECT_EQ(voxels, a.overlaps.features[f].ownVoxels);
  }
}

// Bad tolerances are refused, naming what is wrong.
TEST_F(IncidentalOverlapsTest, BadTolerancesAreRefused) {
  const ContourSet set = thinOverlapContours(1.0);
  for (auto [depth, percent] :
       {std::pair{-1.0, 2.0}, std::pair{std::nan(""), 2.0}, std::pair{0.0, 101.0}, std::pair{0.0, -0.5}}) {
    BuildOptions o = options(1.0);
    o.overlapTolerance.depth = depth;
    o.overlapTolerance.percent = percent;
    auto built = engine_->build(set, o);
    ASSERT_FALSE(built);
    EXPECT_EQ(built.error().code, Errc::InvalidArgument);
    EXPECT_NE(built.error().message.find("overlap tolerance"), std::string::npos);
  }
}

// The overlap analysis alone says what build() does with each pair.
TEST_F(IncidentalOverlapsTest, AnalysisAloneMatchesTheBuild) {
  DrawnPelvisOptions o;
  o.planningVolume = true;
  const ContourSet set = drawnPelvisContours(o);
  const BuildResult b = build(set, options(1.0));
  auto analysis = engine_->analyzeOverlaps(set, options(1.0));
  ASSERT_TRUE(analysis) << analysis.error().message;
  ASSERT_EQ(analysis->shared.size(), b.overlaps.shared.size());
  for (std::size_t s = 0; s < analysis->shared.size(); ++s) {
    EXPECT_EQ(analysis->shared[s].incidental, b.overlaps.shared[s].incidental);
    EXPECT_EQ(analysis->shared[s].givenUpByA, b.overlaps.shared[s].givenUpByA);
  }
  EXPECT_EQ(analysis->layers, b.overlaps.layers);
}

}  // namespace
}  // namespace scansurf::test

namespace scansurf::test {
namespace {

// The split is written into the device's labels in place: the surfaces equal those of the host
// round trip, with and without interpolation, in one layer and beside a PTV's layer.
TEST_F(IncidentalOverlapsTest, SplitOnTheDeviceEqualsTheHostRoundTrip) {
  DrawnPelvisOptions drawn;
  for (bool ptv : {false, true}) {
    drawn.planningVolume = ptv;
    const ContourSet set = drawnPelvisContours(drawn);
    for (int factor : {1, InterpolationOptions::kAuto}) {
      SCOPED_TRACE(std::string(ptv ? "with PTV, " : "") + (factor == 1 ? "interpolation off" : "interpolation auto"));
      BuildOptions o = options(1.0);
      o.interpolation.factor = factor;
      const BuildResult host = build(set, o);
      o.keepLabelVolume = false;
      const BuildResult device = build(set, o);
      EXPECT_EQ(device.surfaces.mesh.positions, host.surfaces.mesh.positions);
      EXPECT_EQ(device.surfaces.mesh.triangles, host.surfaces.mesh.triangles);
      EXPECT_EQ(device.surfaces.mesh.labels, host.surfaces.mesh.labels);
      EXPECT_GT(interfaceTriangles(host, featureNamed(set, "prostate"), featureNamed(set, "rectum")), 100u);
    }
  }
}

}  // namespace
}  // namespace scansurf::test

namespace scansurf::test {
namespace {

// One policy for bad options, at build() and the stage calls alike: refused with
// Errc::InvalidArgument naming the option and its range, never clamped or replaced.
class BuildOptionsTest : public EngineTest {};

TEST_F(BuildOptionsTest, BadOptionsAreRefusedNamingTheOption) {
  const ContourSet set = thinOverlapContours(1.0);
  const auto refused = [&](const BuildOptions& o, const std::string& option) {
    auto built = engine_->build(set, o);
    ASSERT_FALSE(built) << option;
    EXPECT_EQ(built.error().code, Errc::InvalidArgument);
    EXPECT_NE(built.error().message.find("option " + option + " must be"), std::string::npos) << built.error().message;
  };
  BuildOptions o;
  o.grid.voxelSize = 2;
  o.smoothing.enabled = true;
  o.smoothing.strength = 1.5;
  refused(o, "smoothing.strength");
  o.smoothing.strength = 0.8;
  o.smoothing.iterations = 0;
  refused(o, "smoothing.iterations");
  o.smoothing.iterations = 150;
  o.smoothing.minAngle = 45;
  refused(o, "smoothing.minAngle");
  o.smoothing.minAngle = 15;
  o.smoothing.snap = 0.5;
  refused(o, "smoothing.snap");
  o.smoothing.snap = -0.1;
  refused(o, "smoothing.snap");
  o.smoothing.snap = 0.05;
  o.simplification.enabled = true;
  o.simplification.tolerance = 0;
  refused(o, "simplification.tolerance");
  o.simplification.tolerance = 0.05;
  o.simplification.edgeLength = 9;
  refused(o, "simplification.edgeLength");
  o.simplification.edgeLength = 2;
  o.simplification.minAngle = -1;
  refused(o, "simplification.minAngle");
  o.simplification = {};
  o.remeshing.enabled = true;
  o.remeshing.edgeLength = -1;
  refused(o, "remeshing.edgeLength");
  o.remeshing = {};
  o.interpolation.factor = 17;
  refused(o, "interpolation.factor");
  o.interpolation.factor = 1;
  o.threads = -2;
  refused(o, "threads");
  o.threads = BuildOptions::kMostThreads + 1;
  refused(o, "threads");
  o.threads = 0;
  o.smoothing.iterations = SmoothingOptions::kMostIterations + 1;
  refused(o, "smoothing.iterations");
  o.smoothing.iterations = 150;
  // A stage that is off has its options checked too (the report records them).
  o.smoothing.enabled = false;
  o.smoothing.snap = 0.9;
  refused(o, "smoothing.snap");
  o.smoothing.snap = 0.05;
  o.smoothing.minAngle = -5;
  refused(o, "smoothing.minAngle");
  o.smoothing.minAngle = 15;
  o.simplification.enabled = false;
  o.simplification.edgeLength = 100;
  refused(o, "simplification.edgeLength");
  o.simplification = {};
  o.smoothing.enabled = true;
  EXPECT_TRUE(engine_->build(set, o));
  // The stage calls check the same options.
  auto volume = engine_->scanConvert(set, computeNesting(set), *makeGrid(set, o.grid), o);
  ASSERT_TRUE(volume);
  o.smoothing.strength = 0;
  auto extracted = engine_->extract(*volume, computeNesting(set), o, &set);
  ASSERT_FALSE(extracted);
  EXPECT_NE(extracted.error().message.find("smoothing.strength"), std::string::npos);
}

// Simplification through build(): the figures reported, and
// every feature surface still a closed oriented manifold of the same genus and components.
TEST_F(BuildOptionsTest, SimplificationThroughBuildKeepsEverySurface) {
  const ContourSet set = drawnPelvisContours();
  BuildOptions o;
  o.grid.voxelSize = 1.0;
  o.smoothing.enabled = true;
  auto plain = engine_->build(set, o);
  o.simplification.enabled = true;
  auto simplified = engine_->build(set, o);
  ASSERT_TRUE(plain && simplified);
  const SimplificationReport& r = simplified->surfaces.simplification;
  EXPECT_TRUE(r.ran);
  EXPECT_FALSE(plain->surfaces.simplification.ran);
  // Simplification starts from the default's mesh, the cubes' fans included, and ends with
  // fewer triangles.
  EXPECT_EQ(r.trianglesBefore, plain->surfaces.mesh.triangleCount());
  EXPECT_EQ(simplified->surfaces.triangleShape.cubeFans, plain->surfaces.triangleShape.cubeFans);
  EXPECT_GT(simplified->surfaces.triangleShape.cubeFans, 0u);
  EXPECT_EQ(r.trianglesAfter, simplified->surfaces.mesh.triangleCount());
  EXPECT_LT(r.trianglesAfter, r.trianglesBefore * 4 / 5);
  EXPECT_LT(r.trianglesAfter, plain->surfaces.mesh.triangleCount());
  EXPECT_GE(r.anglesAfter.min, r.anglesBefore.min - 1e-3);
  for (std::size_t f = 0; f < set.features.size(); ++f) {
    const MeshStats a = computeMeshStats(plain->surfaces.mesh.positions, plain->surfaces.features[f].triangles);
    const MeshStats b = computeMeshStats(simplified->surfaces.mesh.positions, simplified->surfaces.features[f].triangles);
    EXPECT_TRUE(b.closed && b.manifold && b.oriented) << set.features[f].name;
    EXPECT_EQ(b.genus, a.genus) << set.features[f].name;
    EXPECT_EQ(b.components, a.components) << set.features[f].name;
    EXPECT_NEAR(b.volume, a.volume, 0.01 * a.volume) << set.features[f].name;
  }
  std::printf("[ figure   ] drawn pelvis, 1 mm: %zu -> %zu triangles, %zu patches, %zu refused, %zu crossing, %d layers\n",
              r.trianglesBefore, r.trianglesAfter, r.patches, r.refused, r.crossing, simplified->overlaps.layers);
}

}  // namespace
}  // namespace scansurf::test

namespace scansurf::test {
namespace {

// --overlaps partition is as it was: priority gives every shared voxel, the rule changes
// nothing there (the same surfaces with it on and off).
TEST_F(IncidentalOverlapsTest, PartitionModeIgnoresTheRule) {
  const ContourSet set = drawnPelvisContours();
  BuildOptions on = options(1.0);
  on.overlaps = OverlapMode::Partition;
  BuildOptions off = on;
  off.overlapTolerance.enabled = false;
  const BuildResult a = build(set, on), b = build(set, off);
  EXPECT_EQ(a.overlaps.layers, 1);
  EXPECT_EQ(a.surfaces.mesh.positions, b.surfaces.mesh.positions);
  EXPECT_EQ(a.surfaces.mesh.triangles, b.surfaces.mesh.triangles);
}

}  // namespace
}  // namespace scansurf::test
