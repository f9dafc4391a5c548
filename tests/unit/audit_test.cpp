// The run's audit: the topology a feature's slab volume implies (contour_topology.h) on regions
// drawn by hand, and the audit of surfaces with an injected hole against closed ones.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "geometry/audit/contour_topology.h"
#include "geometry/audit/surface_audit.h"

namespace scansurf {
namespace {

// A region from per-layer pictures: '#' is a pixel of the feature, rows top to bottom.
FeatureRegion regionOf(const std::vector<std::vector<std::string>>& layers) {
  FeatureRegion region;
  region.minRow = region.minColumn = 1 << 20;
  for (std::size_t l = 0; l < layers.size(); ++l) {
    region.layers.push_back(static_cast<int>(l) + 3);
    std::vector<PixelRun> runs;
    for (std::size_t r = 0; r < layers[l].size(); ++r) {
      const std::string& row = layers[l][r];
      for (std::size_t c = 0; c < row.size();) {
        if (row[c] != '#') {
          ++c;
          continue;
        }
        std::size_t end = c;
        while (end < row.size() && row[end] == '#') ++end;
        runs.push_back({static_cast<int>(r) + 5, static_cast<int>(c) + 7, static_cast<int>(end) + 7});
        region.minRow = std::min(region.minRow, static_cast<int>(r) + 5);
        region.maxRow = std::max(region.maxRow, static_cast<int>(r) + 5);
        region.minColumn = std::min(region.minColumn, static_cast<int>(c) + 7);
        region.maxColumn = std::max(region.maxColumn, static_cast<int>(end) + 6);
        c = end;
      }
    }
    region.runs.push_back(std::move(runs));
  }
  return region;
}

void expectTopology(const TopologyRange& t, int minC, int maxC, int minG, int maxG) {
  EXPECT_EQ(t.minComponents, minC);
  EXPECT_EQ(t.maxComponents, maxC);
  EXPECT_EQ(t.minGenus, minG);
  EXPECT_EQ(t.maxGenus, maxG);
}

const std::vector<std::string> kSquare = {"###", "###", "###"};
const std::vector<std::string> kRing = {"###", "#.#", "###"};

TEST(ContourTopology, ASolidIsOneSphere) { expectTopology(contourTopology(regionOf({kSquare, kSquare, kSquare})), 1, 1, 0, 0); }

TEST(ContourTopology, RingsStackedAreATorus) { expectTopology(contourTopology(regionOf({kRing, kRing, kRing})), 1, 1, 1, 1); }

TEST(ContourTopology, AClosedCavityIsASecondSurface) {
  expectTopology(contourTopology(regionOf({kSquare, kRing, kSquare})), 2, 2, 0, 0);
}

TEST(ContourTopology, TwoPartsApartAreTwoSpheres) {
  expectTopology(contourTopology(regionOf({{"##..##", "##..##"}, {"##..##", "##..##"}})), 2, 2, 0, 0);
}

TEST(ContourTopology, ABranchIsStillOneSphere) {
  // One part below, two above: a Y.
  expectTopology(contourTopology(regionOf({{"#####"}, {"#####"}, {"##.##"}, {"##.##"}})), 1, 1, 0, 0);
}

TEST(ContourTopology, ACornerTouchMayGoEitherWay) {
  // Two pixels meeting at a corner: two spheres with 6-adjacency, one with 26.
  expectTopology(contourTopology(regionOf({{"#.", ".#"}})), 1, 2, 0, 0);
}

TEST(ContourTopology, ALayerTheListSkipsPartsThem) {
  // Grid layers the feature has no slice on lie across one of its long gaps (own slabs fill
  // every other): each side is capped on its own, two surfaces.
  FeatureRegion region = regionOf({kSquare, kSquare});
  region.layers = {2, 9};
  expectTopology(contourTopology(region), 2, 2, 0, 0);
  region.layers = {2, 3};
  expectTopology(contourTopology(region), 1, 1, 0, 0);
}

TEST(ContourTopology, AStructureThatMovedFurtherThanItsWidthIsOneTube) {
  // Consecutive layers share no pixel: interpolation follows the centroid shift, one tube.
  expectTopology(contourTopology(regionOf({{"##......", "##......"}, {"......##", "......##"}, {"......##", "......##"}})), 1, 1,
                 0, 0);
}

TEST(ContourTopology, NoPixelsNoSurface) { EXPECT_TRUE(contourTopology(FeatureRegion{}).empty()); }

// An octahedron (closed, genus 0) as feature 0 of a surface set.
Surfaces octahedron() {
  Surfaces s;
  s.mesh.positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  FeatureSurface f;
  f.feature = 0;
  f.triangles = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  s.features.push_back(f);
  return s;
}

ContourSet oneFeature() {
  ContourSet contours;
  contours.source = "hand.json";
  contours.features.push_back({"ball", std::nullopt, {}, 0, ""});
  return contours;
}

TEST(SurfaceAudit, AClosedSurfaceThatMatchesItsContoursIsQuiet) {
  const Surfaces surfaces = octahedron();
  const ContourSet contours = oneFeature();
  const std::vector<FeatureRegion> regions = {regionOf({kSquare, kSquare})};
  const double volume = 4.0 / 3.0;  // the octahedron's
  const SurfaceAudit audit = auditSurfaces({contours, surfaces, regions, {volume}, 0.03, 0, 1});
  EXPECT_TRUE(audit.findings.empty());
  EXPECT_FALSE(audit.defective());
  ASSERT_EQ(audit.stats.size(), 1u);
  EXPECT_TRUE(audit.stats[0].closed);
}

TEST(SurfaceAudit, AnInjectedHoleIsADefectNamingTheFeature) {
  Surfaces surfaces = octahedron();
  surfaces.features[0].triangles.resize(surfaces.features[0].triangles.size() - 3);  // one face gone
  const ContourSet contours = oneFeature();
  const SurfaceAudit audit = auditSurfaces({contours, surfaces, {}, {}, 0.03, 0, 1});
  ASSERT_EQ(audit.findings.size(), 1u);
  EXPECT_TRUE(audit.defective());
  EXPECT_EQ(audit.findings[0].check, AuditCheck::Open);
  EXPECT_NE(audit.findings[0].message.find("\"ball\""), std::string::npos) << audit.findings[0].message;
}

TEST(SurfaceAudit, TopologyAndVolumeOffTheContoursAreFindings) {
  const Surfaces surfaces = octahedron();
  const ContourSet contours = oneFeature();
  // The contours imply a torus and twice the volume.
  const std::vector<FeatureRegion> regions = {regionOf({kRing, kRing, kRing})};
  const SurfaceAudit audit = auditSurfaces({contours, surfaces, regions, {8.0 / 3.0}, 0.03, 0, 1});
  EXPECT_FALSE(audit.defective());
  ASSERT_EQ(audit.findings.size(), 2u);
  EXPECT_EQ(audit.findings[0].check, AuditCheck::Genus);
  EXPECT_EQ(audit.findings[0].expected, 1);
  EXPECT_EQ(audit.findings[0].found, 0);
  EXPECT_NE(audit.findings[0].message.find("genus 0 where its contours imply 1"), std::string::npos) << audit.findings[0].message;
  EXPECT_EQ(audit.findings[1].check, AuditCheck::Volume);
  EXPECT_NE(audit.findings[1].message.find("-50.0 %"), std::string::npos) << audit.findings[1].message;
}

TEST(SurfaceAudit, AVolumeWithinTheToleranceIsQuiet) {
  const Surfaces surfaces = octahedron();
  const ContourSet contours = oneFeature();
  const SurfaceAudit audit = auditSurfaces({contours, surfaces, {}, {4.0 / 3.0 * 1.02}, 0.03, 0, 1});
  EXPECT_TRUE(audit.findings.empty());
}

}  // namespace
}  // namespace scansurf
