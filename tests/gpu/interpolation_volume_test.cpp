// Volumes between the slices: with interpolation (the CLI's default, round caps), structures
// of one, two and three planes keep their contour volume (the slab rule), because each round
// cap is a dome as high as the gap that holds a flat half slab's volume.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "gpu/gpu_test_env.h"
#include "support/intersections.h"
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

// Within 3 % for one and two planes, 1 % for three, at 1 mm pixels (2 px gaps: no layers
// between; relaxation alone took 17 % off the scar and added 4 % to the discs), 0.5 mm (4
// layers a gap) and 0.25 mm (8), every surface closed and none crossing another.
TEST_F(InterpolationVolumeTest, FewPlaneStructuresKeepTheirSlabVolume) {
  const ContourSet set = smallStructures();
  for (double pixel : {1.0, 0.5, 0.25}) {
    const BuildResult b = build(set, pixel);
    ASSERT_EQ(b.interpolation.used(), pixel < 1.0);
    std::printf("[ figure   ] %.2f mm pixels, 2 mm planes:", pixel);
    for (std::size_t f = 0; f < set.features.size(); ++f) {
      const double e = volumeError(b, static_cast<int>(f));
      std::printf(" %s %+.1f %%", set.features[f].name.c_str(), 100 * e);
      const MeshStats s = computeMeshStats(b.surfaces.mesh.positions, b.surfaces.features[f].triangles);
      EXPECT_TRUE(s.closed && s.manifold && s.oriented) << set.features[f].name;
      EXPECT_EQ(s.components, 1) << set.features[f].name;
      EXPECT_LE(std::abs(e), set.features[f].slices.size() >= 3 ? 0.01 : 0.03)
          << set.features[f].name << " at " << pixel << " mm";
    }
    std::printf("\n");
    if (pixel == 1.0) {
      EXPECT_EQ(findCrossings(b.surfaces.mesh.positions, b.surfaces.mesh.triangles).crossings, 0u);
    }
  }
}

}  // namespace
}  // namespace scansurf::test

namespace scansurf::test {
namespace {

// The volumes restored after smoothing are the same for any thread count, bit for bit.
TEST_F(InterpolationVolumeTest, RestoredVolumesAreTheSameForAnyThreadCount) {
  const ContourSet set = smallStructures();
  std::vector<float> first;
  for (int threads : {1, 2, 3}) {
    BuildOptions options;
    options.grid.voxelSize = 1.0;
    options.smoothing.enabled = true;
    options.threads = threads;
    auto built = engine_->build(set, options);
    ASSERT_TRUE(built) << built.error().message;
    if (first.empty())
      first = built->surfaces.mesh.positions;
    else
      EXPECT_EQ(built->surfaces.mesh.positions, first) << threads << " threads";
  }
}

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

namespace scansurf::test {
namespace {

Contour rotatedEllipse(Point2 c, double a, double b, double angle) {
  Contour out = ellipse({0, 0}, a, b);
  for (Point2& p : out.points) {
    const double x = p.x, y = p.y;
    p = {c.x + x * std::cos(angle) - y * std::sin(angle), c.y + x * std::sin(angle) + y * std::cos(angle)};
  }
  return out;
}

Feature onPlanes(const std::string& name, std::initializer_list<std::pair<double, Contour>> slices) {
  Feature f{name, {}, {}};
  for (const auto& [z, contour] : slices) f.slices.push_back({z, {contour}});
  return f;
}

// Outlines that change between planes 5 mm apart (10 layers a gap at 0.5 mm pixels): a disc
// that doubles and shrinks, an ellipse that moves by more than its half-width, one that turns a
// quarter turn, and two half-discs squeezing one another (their shared edge moves 3 mm).
ContourSet changingOutlines() {
  ContourSet set;
  set.source = "changing outlines";
  set.features = {
      onPlanes("grow", {{0, circleContour({30, 0}, 5)}, {5, circleContour({30, 0}, 10)}, {10, circleContour({30, 0}, 6)}}),
      onPlanes("shift", {{0, ellipse({0, 30}, 8, 4)}, {5, ellipse({0, 35}, 8, 4)}, {10, ellipse({0, 30}, 8, 4)}}),
      onPlanes("turn", {{0, rotatedEllipse({30, 30}, 10, 3, 0)},
                        {5, rotatedEllipse({30, 30}, 10, 3, std::numbers::pi / 2)},
                        {10, rotatedEllipse({30, 30}, 10, 3, 0)}})};
  return set;
}

// Both squeezing halves: a disc r 8 split by a vertical line at x = -1.5, 1.5, -1.5 mm.
void addSqueezingPair(ContourSet& set) {
  auto side = [](double split, bool left) {
    Contour c;
    const double h = std::sqrt(64 - split * split);
    const double a0 = std::atan2(h, split), a1 = std::atan2(-h, split);  // where the line meets the circle
    for (int i = 0; i <= 96; ++i) {
      const double t = left ? a0 + (2 * std::numbers::pi - (a0 - a1)) * i / 96.0 : a1 + (a0 - a1) * i / 96.0;
      c.points.push_back({8 * std::cos(t), -30 + 8 * std::sin(t)});
    }
    return c;
  };
  set.features.push_back(onPlanes("left", {{0, side(-1.5, true)}, {5, side(1.5, true)}, {10, side(-1.5, true)}}));
  set.features.push_back(onPlanes("right", {{0, side(-1.5, false)}, {5, side(1.5, false)}, {10, side(-1.5, false)}}));
}

// Each structure's volume follows its slab rule whatever its outline does between the planes
// (the blended fields alone lost 5 %, 8 % and 15 % here), round caps and flat: the layers
// between the planes alone, without the volume restoration after smoothing.
TEST_F(InterpolationVolumeTest, ChangingOutlinesKeepTheirSlabVolume) {
  ContourSet set = changingOutlines();
  addSqueezingPair(set);
  for (CapShape caps : {CapShape::Round, CapShape::Flat}) {
    BuildOptions options;
    options.grid.voxelSize = 0.5;
    options.interpolation.factor = InterpolationOptions::kAuto;
    options.interpolation.caps = caps;
    options.smoothing.enabled = true;
    options.smoothing.keepVolumes = false;
    auto built = engine_->build(set, options);
    ASSERT_TRUE(built) << built.error().message;
    ASSERT_TRUE(built->interpolation.used());
    std::printf("[ figure   ] 0.5 mm pixels, 5 mm planes, %s caps:", caps == CapShape::Round ? "round" : "flat");
    for (std::size_t f = 0; f < set.features.size(); ++f) {
      const double e = volumeError(*built, static_cast<int>(f));
      std::printf(" %s %+.2f %%", set.features[f].name.c_str(), 100 * e);
      EXPECT_LE(std::abs(e), 0.01) << set.features[f].name;
    }
    std::printf("\n");
  }
}

// A structure's volume does not depend on which others are in the set (on the same grid):
// a disc alone and among the changing outlines, and one-section vesicles beside a cell of
// five sections (an EM set) keep their slab, never inflated.
TEST_F(InterpolationVolumeTest, VolumesDoNotDependOnTheOtherStructures) {
  const Feature disc = onPlanes("disc", circleContour({-30, -30}, 10), {0, 5, 10});
  ContourSet alone;
  alone.source = "alone";
  alone.features = {disc};
  ContourSet among = changingOutlines();
  among.features.push_back(disc);
  const double extent[2][2] = {{-45, -45}, {45, 45}};  // one grid for both: a frame around everything
  auto build = [&](ContourSet set) {
    set.features.push_back(onPlanes("frame corner a", circleContour({extent[0][0], extent[0][1]}, 0.6), {5}));
    set.features.push_back(onPlanes("frame corner b", circleContour({extent[1][0], extent[1][1]}, 0.6), {5}));
    BuildOptions options;
    options.grid.voxelSize = 0.5;
    options.interpolation.factor = InterpolationOptions::kAuto;
    options.smoothing.enabled = true;
    auto built = engine_->build(set, options);
    EXPECT_TRUE(built) << built.error().message;
    EXPECT_TRUE(built && built->interpolation.used());
    return built ? std::move(built).value() : BuildResult{};
  };
  const BuildResult a = build(alone), b = build(among);
  const double va = volumeError(a, 0), vb = volumeError(b, static_cast<int>(among.features.size()) - 1);
  std::printf("[ figure   ] disc alone %+.3f %%, among others %+.3f %%\n", 100 * va, 100 * vb);
  EXPECT_NEAR(va, vb, 1e-4);

  ContourSet em;
  em.source = "em";
  Feature cell{"cell", {}, {}};
  for (int k = 0; k < 5; ++k) cell.slices.push_back({0.5 * k, {circleContour({0, 0}, 10)}});
  em.features = {std::move(cell)};
  for (int v = 0; v < 4; ++v)
    em.features.push_back(onPlanes("vesicle " + std::to_string(v), circleContour({14 + 3.0 * v, 0}, 1.0), {0.5 * v + 0.25 * 0}));
  BuildOptions options;
  options.grid.voxelSize = 0.05;
  options.interpolation.factor = InterpolationOptions::kAuto;
  options.smoothing.enabled = true;
  auto built = engine_->build(em, options);
  ASSERT_TRUE(built) << built.error().message;
  ASSERT_TRUE(built->interpolation.used());
  std::printf("[ figure   ] EM: cell of 5 sections and one-section vesicles (0.05 pixels, 0.5 sections):");
  for (std::size_t f = 0; f < em.features.size(); ++f) {
    const double e = volumeError(*built, static_cast<int>(f));
    std::printf(" %+.1f %%", 100 * e);
    EXPECT_LE(std::abs(e), f == 0 ? 0.01 : 0.03) << em.features[f].name;
  }
  std::printf("\n");
}

}  // namespace
}  // namespace scansurf::test
