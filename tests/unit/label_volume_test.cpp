// The label volume of a run (issue 9): every feature's own mask, in layers where features
// share voxels (3D Slicer's seg.nrrd), exactly the CPU reference rasterization of that feature
// alone, on exactly the reference CT's grid; voxels beyond the CT dropped with a warning.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "geometry/overlaps/overlap_analysis.h"
#include "scansurf/engine.h"
#include "scansurf/input.h"
#include "scansurf/nesting.h"
#include "scansurf/outputs.h"
#include "support/nrrd_reader.h"
#include "support/reference_rasterizer.h"
#include "support/rtstruct_builder.h"
#include "support/scratch_dir_test.h"
#include "support/shapes.h"

namespace scansurf {
namespace {

namespace fs = std::filesystem;

// What Engine::build computes before the device work, here on the CPU: enough for the writers.
BuildResult cpuBuild(const ContourSet& contours) {
  BuildResult b;
  b.nesting = computeNesting(contours);
  auto grid = makeGrid(contours, {});
  EXPECT_TRUE(grid) << grid.error().message;
  b.volume.grid = *grid;
  b.subPixelBits = 8;
  b.overlaps = analyzeOverlaps(contours, *grid, b.nesting, rasterizeFeatures(contours, *grid, 8, 1), {});
  return b;
}

// Feature f alone, rasterized by the reference rasterizer on the grid.
LabelVolume alone(const ContourSet& contours, std::size_t f, const Grid& grid) {
  ContourSet one;
  one.features.push_back(contours.features[f]);
  return test::referenceScanConvert(one, grid, {0}, 8);
}

// Checks the file against the reference, voxel for voxel, and its lattice against the CT's.
void expectMasksOnCt(const fs::path& file, const ContourSet& contours, const BuildResult& built) {
  const test::Nrrd n = test::readNrrd(file);
  const GridReference& ct = *contours.reference;
  const std::vector<double> sizes = test::nrrdNumbers(n.fields.at("sizes"));
  const std::size_t layers = sizes.size() == 4 ? static_cast<std::size_t>(sizes[0]) : 1;
  ASSERT_EQ(sizes.size(), layers > 1 ? 4u : 3u);
  EXPECT_EQ(sizes[sizes.size() - 3], ct.nx);
  EXPECT_EQ(sizes[sizes.size() - 2], ct.ny);
  EXPECT_EQ(sizes[sizes.size() - 1], static_cast<double>(ct.sliceZ.size()));
  const std::vector<double> origin = test::nrrdNumbers(n.fields.at("space origin"));
  EXPECT_NEAR(origin[0], ct.originX, 1e-9);
  EXPECT_NEAR(origin[1], ct.originY, 1e-9);
  EXPECT_NEAR(origin[2], ct.sliceZ.front(), 1e-9);
  const std::vector<double> axes = test::nrrdNumbers(n.fields.at("space directions"));
  EXPECT_NEAR(axes[0], ct.spacingX, 1e-12);
  EXPECT_NEAR(axes[4], ct.spacingY, 1e-12);
  const Grid& grid = built.volume.grid;
  const int ox = static_cast<int>(std::lround((ct.originX - grid.originX) / grid.spacingX));
  const int oy = static_cast<int>(std::lround((ct.originY - grid.originY) / grid.spacingY));
  ASSERT_EQ(n.data.size(), layers * static_cast<std::size_t>(ct.nx) * ct.ny * ct.sliceZ.size());
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    const std::string key = "Segment" + std::to_string(f) + "_";
    const auto layer = static_cast<std::size_t>(std::stoi(n.fields.at(key + "Layer")));
    const int value = std::stoi(n.fields.at(key + "LabelValue"));
    EXPECT_EQ(n.fields.at(key + "Name"), contours.features[f].name);
    const LabelVolume expected = alone(contours, f, grid);
    std::size_t mismatches = 0, voxels = 0;
    for (std::size_t k = 0; k < ct.sliceZ.size(); ++k) {
      const int gk = nearestLayer(grid, ct.sliceZ[k]);  // CT slices between contour planes: the nearer plane
      for (int j = 0; j < ct.ny; ++j)
        for (int i = 0; i < ct.nx; ++i) {
          const std::size_t at =
              layers * (static_cast<std::size_t>(i) + ct.nx * (static_cast<std::size_t>(j) + ct.ny * k)) + layer;
          const bool inFile = static_cast<unsigned char>(n.data[at]) == value;
          const bool inReference = expected.at(i + ox, j + oy, gk) != 0;
          mismatches += inFile != inReference;
          voxels += inReference;
        }
    }
    SCOPED_TRACE(contours.features[f].name);
    EXPECT_EQ(mismatches, 0u);
    EXPECT_GT(voxels, 0u);
  }
}

class LabelVolumeTest : public test::ScratchDirTest {};

// A CT written in the test; BODY holds an organ, a PTV partly overlaps the organ, and a skin
// mark reaches beyond the CT's edge.
TEST_F(LabelVolumeTest, OwnMasksInLayersOnTheCtGrid) {
  test::TestCt ct;
  ct.columns = 40, ct.rows = 36, ct.spacingX = 0.9, ct.spacingY = 0.8, ct.originX = -18.1, ct.originY = -14.3;
  ct.sliceZ = {-4, -2, 0, 2, 4};
  test::writeTestCtSeries(ct, dir_ / "ct");
  const auto circle = [](double cx, double cy, double r) { return circleContour({cx, cy}, r).points; };
  test::TestRtStruct rt;
  test::TestRoi body{1, "BODY", "EXTERNAL", std::nullopt, {}}, organ{2, "organ", "ORGAN", std::nullopt, {}},
      ptv{3, "PTV", "PTV", std::nullopt, {}}, mark{4, "mark", "MARKER", std::nullopt, {}};
  for (double z : {-2.0, 0.0, 2.0}) {
    body.contours.push_back(test::closedContour(circle(0, 0, 13), z));
    organ.contours.push_back(test::closedContour(circle(-3, 0, 5), z));
    ptv.contours.push_back(test::closedContour(circle(2, 1, 4), z));
    mark.contours.push_back(test::closedContour(circle(17, 0, 3), z));
  }
  rt.rois = {body, organ, ptv, mark};
  test::writeTestRtStruct(rt, dir_ / "rt.dcm");
  ReadOptions options;
  options.referenceSeries = dir_ / "ct";
  auto contours = readContours(dir_ / "rt.dcm", options);
  ASSERT_TRUE(contours) << contours.error().message;
  ASSERT_TRUE(contours->reference);
  const BuildResult built = cpuBuild(*contours);
  EXPECT_GE(built.overlaps.maskLayers, 2);
  std::vector<std::string> warnings;
  ASSERT_TRUE(writeLabelVolume(dir_ / "labels.seg.nrrd", *contours, built, &warnings));
  expectMasksOnCt(dir_ / "labels.seg.nrrd", *contours, built);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("\"mark\""), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("beyond the reference CT"), std::string::npos) << warnings[0];
}

// The MIM phantom's structure set on its own CT (512 x 512 x 5): the file has exactly the CT's
// size, origin and spacing, each ROI's mask its own rasterization.
TEST_F(LabelVolumeTest, MimPhantomOnItsCt) {
  const fs::path mim = fs::path(SCANSURF_RTSTRUCT_SAMPLES) / "rt-utils" / "mim_phantom";
  if (!fs::exists(mim / "rt.dcm")) GTEST_SKIP() << "no " << mim;
  ReadOptions options;
  options.referenceSeries = mim;
  auto contours = readContours(mim / "rt.dcm", options);
  ASSERT_TRUE(contours) << contours.error().message;
  const BuildResult built = cpuBuild(*contours);
  ASSERT_TRUE(writeLabelVolume(dir_ / "mim.nrrd", *contours, built));
  expectMasksOnCt(dir_ / "mim.nrrd", *contours, built);
}

}  // namespace
}  // namespace scansurf
