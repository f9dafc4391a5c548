// DICOM input: RT Structure Sets and CT series written with DCMTK in the test (nested,
// abutting, holes, keyholes, islands, uneven slices, POINT and empty ROIs, every bad input),
// surfaced with the CPU pipeline; and the public samples in ../shared/data/rtstruct.
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcxfer.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <tuple>

#include "geometry/extraction/assembly.h"
#include "geometry/extraction/cell_cases.h"
#include "geometry/extraction/feature_surfaces.h"
#include "geometry/overlaps/label_layers.h"
#include "io/ct_series.h"
#include "io/dicom_nesting.h"
#include "io/rtstruct_reader.h"
#include "scansurf/grid.h"
#include "scansurf/nesting.h"
#include "support/reference_rasterizer.h"
#include "support/rtstruct_builder.h"
#include "support/scratch_dir_test.h"
#include "support/shapes.h"

namespace scansurf {
namespace {

namespace fs = std::filesystem;
using test::closedContour;
using test::TestContour;
using test::TestRoi;
using test::TestRtStruct;

std::vector<Point2> square(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

class Dicom : public test::ScratchDirTest {
 protected:
  fs::path write(const TestRtStruct& rt, const std::string& name = "rt.dcm") {
    const fs::path p = dir_ / name;
    test::writeTestRtStruct(rt, p);
    return p;
  }
  Result<RtStructure> readBack(const TestRtStruct& rt, RtStructOptions options = {}) { return readRtStruct(write(rt), options); }
  // The error message of reading rt, which must fail with `code`.
  std::string errorOf(const TestRtStruct& rt, Errc code = Errc::InvalidInput) {
    auto r = readBack(rt);
    EXPECT_FALSE(r);
    if (r) return {};
    EXPECT_EQ(r.error().code, code) << r.error().message;
    return r.error().message;
  }
};

// The whole method on the CPU (reference rasterizer, reference classification, assembly).
struct Built {
  Nesting nesting;
  LabelVolume volume;
  MultiLabelMesh mesh;
  std::vector<FeatureSurface> features;
  MeshStats stats(int f) const { return computeMeshStats(mesh.positions, features[static_cast<std::size_t>(f)].triangles); }
};

Built buildCpu(const ContourSet& set, const GridOptions& options) {
  Built b;
  b.nesting = computeNesting(set);
  auto grid = makeGrid(set, options);
  EXPECT_TRUE(grid) << grid.error().message;
  if (!grid) return b;
  b.volume = test::referenceScanConvert(set, *grid, b.nesting.order, 8);
  const auto cells = classifyCellsReference(b.volume);
  b.mesh = assembleMesh(*grid, cells);
  b.features = extractFeatureSurfaces(b.mesh, static_cast<int>(set.features.size()), b.nesting, SurfaceConvention::Enclosing);
  return b;
}

GridOptions voxels(double size) {
  GridOptions o;
  o.voxelSize = size;
  return o;
}

void expectClosed(const Built& b, const ContourSet& set) {
  for (std::size_t f = 0; f < set.features.size(); ++f) {
    const MeshStats s = b.stats(static_cast<int>(f));
    EXPECT_GT(s.triangles, 0u) << set.features[f].name;
    EXPECT_TRUE(s.closed && s.manifold && s.oriented) << set.features[f].name;
    EXPECT_GT(s.volume, 0) << set.features[f].name;
  }
}

// The voxel nearest to (x, y) on the layer at z.
Label labelAt(const LabelVolume& v, double x, double y, double z) {
  const Grid& g = v.grid;
  const int i = static_cast<int>(std::lround((x - g.originX) / g.spacingX));
  const int j = static_cast<int>(std::lround((y - g.originY) / g.spacingY));
  const int k = layerOfZ(g, z, 1e-6);
  EXPECT_GE(k, 0) << "no layer at z=" << z;
  return k < 0 ? Label(0xffff) : v.at(i, j, k);
}

// ---------------------------------------------------------------------------------------
// Reading

TEST_F(Dicom, NestedRoisWithSliceJitterShareTheirPlanes) {
  TestRtStruct rt;
  TestRoi body{1, "BODY", "EXTERNAL", Rgb{10, 20, 30}, {}};
  TestRoi organ{2, "organ", "ORGAN", Rgb{255, 0, 0}, {}};
  const std::vector<double> zs = {0, 2.5, 5, 7.5, 10, 12.5};
  for (double z : zs) {
    body.contours.push_back(closedContour(square(-20, -20, 20, 20), z));
    // The organ's planes carry the rounding real files have (12.4999 beside 12.5).
    organ.contours.push_back(closedContour(square(-5, -5, 5, 5), z == 12.5 ? 12.4999 : z == 5 ? 5.00004 : z));
  }
  rt.rois = {organ, body};  // organ first: the nesting order must still put BODY outermost
  auto r = readBack(rt);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->contours.features.size(), 2u);
  EXPECT_EQ(r->contours.features[0].name, "organ");
  EXPECT_EQ(r->contours.features[1].name, "BODY");
  EXPECT_EQ(r->contours.features[1].color, (Rgb{10, 20, 30}));
  EXPECT_EQ(r->contours.units, "mm");
  ASSERT_EQ(r->rois.size(), 2u);
  EXPECT_EQ(r->rois[1].interpretedType, "EXTERNAL");
  EXPECT_EQ(r->rois[1].number, 1);
  EXPECT_EQ(r->rois[0].slices, 6);
  EXPECT_EQ(r->referencedSeriesUids, (std::vector<std::string>{"1.2.826.0.1.3680043.2.1125.9.2"}));
  // Each plane is the most frequent z of its group: both ROIs land on exactly 12.5 and 5.
  for (std::size_t s = 0; s < zs.size(); ++s) {
    EXPECT_EQ(r->contours.features[0].slices[s].z, zs[s]);
    EXPECT_EQ(r->contours.features[1].slices[s].z, zs[s]);
  }
  const Built b = buildCpu(r->contours, voxels(1));
  EXPECT_EQ(b.nesting.order, (std::vector<int>{0, 1}));
  EXPECT_EQ(b.volume.grid.nz, 8);
  EXPECT_EQ(labelAt(b.volume, 0, 0, 5), labelOfFeature(0));
  EXPECT_EQ(labelAt(b.volume, 15, 0, 5), labelOfFeature(1));
  expectClosed(b, r->contours);
  // BODY encloses the organ (enclosing convention): 40 x 40 x 15 mm (slab of 6 slices, 2.5 mm apart).
  EXPECT_NEAR(b.stats(1).volume, 40.0 * 40.0 * 15.0, 0.08 * 40 * 40 * 15);
  EXPECT_NEAR(b.stats(0).volume, 10.0 * 10.0 * 15.0, 0.25 * 10 * 10 * 15);
}

TEST_F(Dicom, ExternalRoiComesLastSoAnOrganPokingOutKeepsItsVoxels) {
  TestRoi body{1, "BODY", "EXTERNAL", std::nullopt, {}};
  TestRoi organ{2, "organ", "ORGAN", std::nullopt, {}};
  for (double z : {0.0, 2.0, 4.0}) {
    body.contours.push_back(closedContour(square(-20, -20, 20, 20), z));
    // On z = 2 the organ reaches outside BODY, so BODY does not contain it.
    organ.contours.push_back(closedContour(square(-5, -5, z == 2 ? 25 : 5, 5), z));
  }
  TestRtStruct rt;
  rt.rois = {body, organ};
  auto r = readBack(rt);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->contours.features.size(), 2u);
  EXPECT_EQ(r->contours.features[0].name, "organ");
  EXPECT_EQ(r->contours.features[1].name, "BODY");
  EXPECT_EQ(r->rois[0].feature, 1);
  EXPECT_EQ(r->rois[1].feature, 0);
  const Built b = buildCpu(r->contours, voxels(1));
  EXPECT_EQ(b.nesting.parent[0], -1);
  EXPECT_EQ(labelAt(b.volume, 0, 0, 2), labelOfFeature(0));
  EXPECT_EQ(labelAt(b.volume, 0, 0, 0), labelOfFeature(0));
  EXPECT_EQ(labelAt(b.volume, 22, 0, 2), labelOfFeature(0));
  EXPECT_EQ(labelAt(b.volume, -15, 0, 2), labelOfFeature(1));
}

TEST_F(Dicom, AbuttingRoisShareOneInterface) {
  TestRtStruct rt;
  TestRoi left{1, "left", "ORGAN", std::nullopt, {}};
  TestRoi right{2, "right", "ORGAN", std::nullopt, {}};
  for (double z : {0.0, 3.0, 6.0}) {
    left.contours.push_back(closedContour(square(-10.3, -8.3, 0.2, 8.3), z));
    right.contours.push_back(closedContour(square(0.2, -8.3, 10.3, 8.3), z));
  }
  rt.rois = {left, right};
  auto r = readBack(rt);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_FALSE(r->contours.features[0].color.has_value());
  const Built b = buildCpu(r->contours, voxels(1));
  expectClosed(b, r->contours);
  EXPECT_EQ(labelAt(b.volume, -0.2, 0, 3), labelOfFeature(0));
  EXPECT_EQ(labelAt(b.volume, 0.8, 0, 3), labelOfFeature(1));
  // Triangles between the two labels exist: they abut, no background gap.
  std::size_t shared = 0;
  for (std::size_t t = 0; t < b.mesh.labels.size(); t += 2)
    shared += b.mesh.labels[t] == labelOfFeature(0) && b.mesh.labels[t + 1] == labelOfFeature(1);
  EXPECT_GT(shared, 0u);
}

TEST_F(Dicom, HoleAndKeyholeGiveTheSameLabels) {
  // One ROI with an outer and an inner contour on each slice (even-odd: a hole), and the same
  // shape as one keyhole contour: outer ring, a zero-width channel at y = 0.37 to the hole,
  // the hole traced the other way round, back along the channel.
  auto holes = TestRoi{1, "ring", "ORGAN", std::nullopt, {}};
  auto keyhole = TestRoi{1, "ring", "ORGAN", std::nullopt, {}};
  for (double z : {0.0, 2.0, 4.0, 6.0}) {
    holes.contours.push_back(closedContour(square(-12, -12, 12, 12), z));
    holes.contours.push_back(closedContour(square(-5.5, -5.5, 5.5, 5.5), z));
    keyhole.contours.push_back(closedContour({{-12, -12},
                                              {12, -12},
                                              {12, 0.37},
                                              {5.5, 0.37},
                                              {5.5, -5.5},
                                              {-5.5, -5.5},
                                              {-5.5, 5.5},
                                              {5.5, 5.5},
                                              {5.5, 0.37},
                                              {12, 0.37},
                                              {12, 12},
                                              {-12, 12}},
                                             z));
  }
  TestRtStruct a, b;
  a.rois = {holes};
  b.rois = {keyhole};
  auto ra = readRtStruct(write(a, "holes.dcm"));
  auto rb = readRtStruct(write(b, "keyhole.dcm"));
  ASSERT_TRUE(ra) << ra.error().message;
  ASSERT_TRUE(rb) << rb.error().message;
  const Built ba = buildCpu(ra->contours, voxels(1));
  const Built bb = buildCpu(rb->contours, voxels(1));
  ASSERT_EQ(ba.volume.grid.nx, bb.volume.grid.nx);
  EXPECT_EQ(ba.volume.labels, bb.volume.labels);
  EXPECT_EQ(labelAt(ba.volume, 0, 0, 2), kBackground);
  EXPECT_EQ(labelAt(ba.volume, 9, 0, 2), labelOfFeature(0));
  EXPECT_EQ(labelAt(bb.volume, 0, 0, 2), kBackground);
  EXPECT_EQ(labelAt(bb.volume, 9, 0.37, 2), labelOfFeature(0));
  expectClosed(ba, ra->contours);
  const MeshStats s = bb.stats(0);
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.genus, 1);  // a tube: the hole goes through every slice
  EXPECT_EQ(s.components, 1);
}

TEST_F(Dicom, IslandsAreSeparateComponents) {
  TestRoi roi{1, "nodes", "ORGAN", std::nullopt, {}};
  for (double z : {0.0, 2.0, 4.0}) {
    roi.contours.push_back(closedContour(square(-10, -3, -4, 3), z));
    roi.contours.push_back(closedContour(square(4, -3, 10, 3), z));
  }
  TestRtStruct rt;
  rt.rois = {roi};
  auto r = readBack(rt);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->contours.features[0].slices.size(), 3u);
  EXPECT_EQ(r->contours.features[0].slices[0].contours.size(), 2u);
  const Built b = buildCpu(r->contours, voxels(1));
  const MeshStats s = b.stats(0);
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.components, 2);
  EXPECT_EQ(labelAt(b.volume, 0, 0, 2), kBackground);
}

TEST_F(Dicom, ARenamedDuplicateNeverTakesAnotherRoisName) {
  TestRtStruct rt;
  for (const auto& [number, name] : std::vector<std::pair<int, std::string>>{{1, "A"}, {2, "A #3"}, {3, "A"}}) {
    TestRoi roi{number, name, "ORGAN", std::nullopt, {}};
    for (double z : {0.0, 2.0}) roi.contours.push_back(closedContour(square(10 * number, 0, 10 * number + 5, 5), z));
    rt.rois.push_back(roi);
  }
  auto r = readBack(rt);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->contours.features.size(), 3u);
  std::vector<std::string> names;
  for (const Feature& f : r->contours.features) names.push_back(f.name);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"A", "A #3", "A #3 (2)"}));
}

// Names follow the Specific Character Set into UTF-8; without one, Latin-1 bytes are read as
// Latin-1 with a warning; UTF-8 stays as it is.
TEST_F(Dicom, NamesAreDecodedFromTheirCharacterSet) {
  const std::string latin1 = "L\xE8vre", utf8 = "L\xC3\xA8vre";
  for (const auto& [charset, name, warned] : std::vector<std::tuple<std::string, std::string, bool>>{
           {"ISO_IR 100", latin1, false}, {"", latin1, true}, {"ISO_IR 192", utf8, false}}) {
    SCOPED_TRACE("Specific Character Set '" + charset + "'");
    TestRtStruct rt;
    rt.specificCharacterSet = charset;
    TestRoi roi{1, name, "ORGAN", std::nullopt, {}};
    for (double z : {0.0, 2.0}) roi.contours.push_back(closedContour(square(0, 0, 5, 5), z));
    rt.rois.push_back(roi);
    auto r = readBack(rt);
    ASSERT_TRUE(r) << r.error().message;
    ASSERT_EQ(r->contours.features.size(), 1u);
    EXPECT_EQ(r->contours.features[0].name, utf8);
    EXPECT_EQ(r->rois[0].name, utf8);
    const bool hasWarning = std::any_of(r->warnings.begin(), r->warnings.end(),
                                        [](const std::string& w) { return w.find("read as Latin-1") != std::string::npos; });
    EXPECT_EQ(hasWarning, warned);
  }
}

TEST_F(Dicom, UnevenSlicesBecomeUnevenLayers) {
  TestRoi roi{1, "cone", "ORGAN", std::nullopt, {}};
  const std::vector<double> zs = {-3, -2, 0.5, 4.5, 5};
  for (double z : zs) roi.contours.push_back(closedContour(square(-6 + z * 0.5, -6, 6, 6), z));
  TestRtStruct rt;
  rt.rois = {roi};
  auto r = readBack(rt);
  ASSERT_TRUE(r) << r.error().message;
  const Built b = buildCpu(r->contours, voxels(1));
  EXPECT_EQ(b.volume.grid.layerZ, (std::vector<double>{-4, -3, -2, 0.5, 4.5, 5, 5.5}));
  expectClosed(b, r->contours);
}

TEST_F(Dicom, PointOpenAndEmptyRoisAreSkippedWithOneWarningEach) {
  TestRoi organ{1, "organ", "ORGAN", std::nullopt, {}};
  organ.contours.push_back(closedContour(square(0, 0, 4, 4), 0));
  organ.contours.push_back(closedContour(square(0, 0, 4, 4), 1));
  TestRoi iso{2, "iso", "ISOCENTER", std::nullopt, {}};
  iso.contours.push_back(TestContour{"POINT", {{1, 2, 0}}, std::nullopt});
  iso.contours.push_back(TestContour{"POINT", {{1, 2, 1}}, std::nullopt});
  TestRoi line{3, "marker", "MARKER", std::nullopt, {}};
  line.contours.push_back(TestContour{"OPEN_PLANAR", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, std::nullopt});
  line.contours.push_back(TestContour{"OPEN_NONPLANAR", {{0, 0, 0}, {1, 0, 1}}, std::nullopt});
  TestRoi empty{4, "empty", "ORGAN", std::nullopt, {}};
  TestRoi noItem{5, "no contour item", "ORGAN", std::nullopt, {}};
  noItem.contourItem = false;
  TestRtStruct rt;
  rt.rois = {organ, iso, line, empty, noItem};
  auto r = readBack(rt);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->contours.features.size(), 1u);
  ASSERT_EQ(r->rois.size(), 5u);
  EXPECT_EQ(r->rois[1].contoursByType.at("POINT"), 2);
  EXPECT_EQ(r->rois[1].feature, -1);
  EXPECT_EQ(r->rois[0].feature, 0);
  ASSERT_EQ(r->warnings.size(), 4u);
  EXPECT_NE(r->warnings[0].find("ROI \"iso\" (#2): skipped 2 POINT contour(s)"), std::string::npos) << r->warnings[0];
  EXPECT_NE(r->warnings[1].find("skipped 2 OPEN_NONPLANAR, OPEN_PLANAR contour(s)"), std::string::npos) << r->warnings[1];
  EXPECT_NE(r->warnings[2].find("\"empty\" (#4): no contours"), std::string::npos) << r->warnings[2];
  EXPECT_NE(r->warnings[3].find("\"no contour item\" (#5): no contours"), std::string::npos) << r->warnings[3];

  // Only POINT ROIs: nothing to surface is an error, but listing still works.
  TestRtStruct points;
  points.rois = {iso};
  EXPECT_NE(errorOf(points).find("no ROI has CLOSED_PLANAR contours"), std::string::npos);
  RtStructOptions listing;
  listing.requireFeatures = false;
  auto listed = readBack(points, listing);
  ASSERT_TRUE(listed) << listed.error().message;
  EXPECT_EQ(listed->rois.size(), 1u);
  EXPECT_DOUBLE_EQ(listed->rois[0].zMax, 1);
}

TEST_F(Dicom, RoiSelectionByGlob) {
  TestRtStruct rt;
  for (int n = 1; n <= 3; ++n) {
    TestRoi roi{n, n == 1 ? "Lung_L" : n == 2 ? "Lung_R" : "Heart", "ORGAN", std::nullopt, {}};
    roi.contours.push_back(closedContour(square(n * 10, 0, n * 10 + 5, 5), 0));
    rt.rois.push_back(roi);
  }
  RtStructOptions o;
  o.roiPatterns = {"lung_*"};
  auto r = readBack(rt, o);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->contours.features.size(), 2u);
  EXPECT_EQ(r->contours.features[1].name, "Lung_R");
  EXPECT_FALSE(r->rois[2].selected);
  o.roiPatterns = {"Heart", "Lung_?"};
  r = readBack(rt, o);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->contours.features.size(), 3u);
  o.roiPatterns = {"Liver"};
  r = readBack(rt, o);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidArgument);
  EXPECT_NE(r.error().message.find("the ROI pattern \"Liver\" matches no ROI; the file holds \"Lung_L\", \"Lung_R\", \"Heart\""),
            std::string::npos)
      << r.error().message;
  EXPECT_TRUE(roiNameMatches("[bB]ody*", "BODY_ext"));
  EXPECT_FALSE(roiNameMatches("bod", "BODY"));
}

TEST_F(Dicom, FileWithoutPart10HeaderReads) {
  TestRtStruct rt;
  rt.fileHeader = false;
  TestRoi roi{7, "box", "ORGAN", std::nullopt, {}};
  roi.contours.push_back(closedContour(square(0, 0, 3, 3), 1));
  rt.rois = {roi};
  const fs::path p = write(rt);
  EXPECT_FALSE(hasDicomPreamble(p));
  auto r = readRtStruct(p);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->rois[0].number, 7);
}

TEST(SlicePlanes, GroupByToleranceAndMostFrequentValue) {
  EXPECT_EQ(groupSlicePlanes({12.5, 12.4999, 12.5, 10, 10.004}, 0.01), (std::vector<double>{12.5, 12.5, 12.5, 10, 10}));
  // Values further apart than the tolerance stay apart.
  EXPECT_EQ(groupSlicePlanes({1, 1.02}, 0.01), (std::vector<double>{1, 1.02}));
  EXPECT_EQ(groupSlicePlanes({7.4999, 7.5}, 0.01), (std::vector<double>{7.5, 7.5}));
  EXPECT_EQ(groupSlicePlanes({7.4999, 7.5, 7.4999}, 0.01), (std::vector<double>{7.4999, 7.4999, 7.4999}));
  EXPECT_TRUE(groupSlicePlanes({}, 0.01).empty());
}

// ---------------------------------------------------------------------------------------
// Bad input: each a clear error naming the file (and ROI and contour), never a crash.

TestRtStruct oneRoi(TestContour contour) {
  TestRtStruct rt;
  TestRoi roi{3, "PTV", "PTV", std::nullopt, {}};
  roi.contours.push_back(closedContour(square(0, 0, 4, 4), 0));
  roi.contours.push_back(std::move(contour));
  rt.rois = {roi};
  return rt;
}

TEST_F(Dicom, NotDicom) {
  const fs::path p = dir_ / "notes.dcm";
  std::ofstream(p) << "{\"this\": \"is JSON, not DICOM\"}\n";
  auto r = readRtStruct(p);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidInput);
  EXPECT_EQ(r.error().message, p.string() + ": not a DICOM file");
  // Binary noise with a DICM preamble but nothing valid after it.
  const fs::path q = dir_ / "noise.dcm";
  {
    std::ofstream out(q, std::ios::binary);
    std::string bytes(128, '\0');
    bytes += "DICM";
    for (int i = 0; i < 64; ++i) bytes += static_cast<char>((i * 37) & 0xff);
    out << bytes;
  }
  r = readRtStruct(q);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidInput);
  EXPECT_EQ(r.error().message.rfind(q.string() + ": ", 0), 0u) << r.error().message;
  // Missing file: an I/O error.
  r = readRtStruct(dir_ / "missing.dcm");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::Io);
}

TEST_F(Dicom, DicomButNotRtStruct) {
  test::TestCt ct;
  ct.sliceZ = {0};
  test::writeTestCtSeries(ct, dir_ / "ct");
  auto r = readRtStruct(dir_ / "ct" / "ct_0.dcm");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("ct_0.dcm: a DICOM CT object (SOP class CTImageStorage), not an RT Structure Set"),
            std::string::npos)
      << r.error().message;
}

TEST_F(Dicom, MissingRequiredAttributes) {
  TestRtStruct rt = oneRoi(closedContour(square(0, 0, 4, 4), 1));
  rt.structureSetRoiSequence = false;
  EXPECT_NE(errorOf(rt).find("rt.dcm: missing required Structure Set ROI Sequence (3006,0020)"), std::string::npos);
  rt = oneRoi(closedContour(square(0, 0, 4, 4), 1));
  rt.roiContourSequence = false;
  EXPECT_NE(errorOf(rt).find("missing required ROI Contour Sequence (3006,0039)"), std::string::npos);
  rt = oneRoi(closedContour(square(0, 0, 4, 4), 1));
  rt.rois[0].writeNumber = false;
  EXPECT_NE(errorOf(rt).find("Structure Set ROI Sequence item 1: missing ROI Number (3006,0022)"), std::string::npos);
  rt = oneRoi(TestContour{"CLOSED_PLANAR", {}, std::string()});
  EXPECT_NE(errorOf(rt).find("ROI \"PTV\" (#3), contour item 2: missing Contour Data (3006,0050)"), std::string::npos);
  rt = oneRoi(TestContour{"CLOSED_PLANAR", {}, std::nullopt});
  const std::string noData = errorOf(rt);
  EXPECT_NE(noData.find("ROI \"PTV\" (#3), contour item 2: missing Contour Data (3006,0050)"), std::string::npos) << noData;
  rt = oneRoi(TestContour{"", {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}}, std::nullopt});
  EXPECT_NE(errorOf(rt).find("contour item 2: missing Contour Geometric Type (3006,0042)"), std::string::npos);
}

TEST_F(Dicom, ContourDataNotTriplets) {
  const auto rt = oneRoi(TestContour{"CLOSED_PLANAR", {}, std::string("0\\0\\1\\4\\0\\1\\4\\4")});
  EXPECT_NE(
      errorOf(rt).find("rt.dcm: ROI \"PTV\" (#3), contour item 2: Contour Data (3006,0050) holds 8 values, not a multiple of 3"),
      std::string::npos);
}

TEST_F(Dicom, NonFiniteAndNonNumericValues) {
  auto message = errorOf(oneRoi(TestContour{"CLOSED_PLANAR", {}, std::string("0\\0\\1\\4\\NaN\\1\\4\\4\\1")}));
  EXPECT_NE(message.find("ROI \"PTV\" (#3), contour item 2"), std::string::npos) << message;
  EXPECT_TRUE(message.find("point 1: non-finite coordinate") != std::string::npos ||
              message.find("is not a list of numbers") != std::string::npos)
      << message;
  message = errorOf(oneRoi(TestContour{"CLOSED_PLANAR", {}, std::string("0\\0\\1\\4\\0\\1\\inf\\4\\1")}));
  EXPECT_NE(message.find("contour item 2"), std::string::npos) << message;
  message = errorOf(oneRoi(TestContour{"CLOSED_PLANAR", {}, std::string("0\\0\\1\\4\\zero\\1\\4\\4\\1")}));
  EXPECT_NE(message.find("contour item 2: Contour Data (3006,0050) is not a list of numbers"), std::string::npos) << message;
}

TEST_F(Dicom, NonAxialAndNonPlanarContoursNamed) {
  // A sagittal contour (x constant).
  auto message = errorOf(oneRoi(TestContour{"CLOSED_PLANAR", {{2, 0, 0}, {2, 4, 0}, {2, 4, 4}, {2, 0, 4}}, std::nullopt}));
  EXPECT_NE(message.find("ROI \"PTV\" (#3), contour item 2: it is not axial: it lies in the plane with normal (1, 0, 0)"),
            std::string::npos)
      << message;
  // A twisted quadrilateral.
  message = errorOf(oneRoi(TestContour{"CLOSED_PLANAR", {{0, 0, 0}, {4, 0, 1}, {4, 4, 0}, {0, 4, 1}}, std::nullopt}));
  EXPECT_NE(message.find("contour item 2: it is not planar: its points span z 0 .. 1 mm"), std::string::npos) << message;
}

// Issue 15, cause 4: Contour Data is parsed once and sequences are walked, never indexed, so
// reading is linear in the file's size (a quadratic reader takes minutes on either).
TEST_F(Dicom, ContourOf200000PointsReads) {
  constexpr int kPoints = 200000;
  std::vector<Point2> circle;
  for (int i = 0; i < kPoints; ++i) {
    const double a = 2 * 3.14159265358979 * i / kPoints;
    circle.push_back({40 * std::cos(a), 40 * std::sin(a)});
  }
  TestRtStruct rt;
  rt.rois.push_back(TestRoi{1, "Big", "ORGAN", std::nullopt, {closedContour(circle, 0), closedContour(circle, 2)}});
  auto r = readBack(rt);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->contours.features.size(), 1u);
  EXPECT_EQ(r->contours.features[0].slices[0].contours[0].points.size(), static_cast<std::size_t>(kPoints));
}

TEST_F(Dicom, TenThousandRoisRead) {
  constexpr int kRois = 10000;
  TestRtStruct rt;
  for (int i = 0; i < kRois; ++i) {
    const double x = 3.0 * (i % 100), y = 3.0 * (i / 100);
    std::string name = std::to_string(i);
    name.insert(name.begin(), 'R');  // not "R" + ...: GCC 12 warns on it, wrongly (-Wrestrict)
    rt.rois.push_back(TestRoi{i + 1, name, "ORGAN", std::nullopt, {closedContour(square(x, y, x + 2, y + 2), 0)}});
  }
  auto r = readBack(rt);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->contours.features.size(), static_cast<std::size_t>(kRois));
  EXPECT_EQ(r->contours.features.back().name, "R9999");
}

// A bare implicit-VR data set claiming to be an RTSTRUCT whose ROI Contour Sequence nests
// `depth` levels deep (sequence, item, sequence, ...), every length undefined.
std::string deeplyNestedRtStruct(int depth) {
  std::string bytes;
  auto u16 = [&](unsigned v) { bytes += static_cast<char>(v & 0xff), bytes += static_cast<char>(v >> 8 & 0xff); };
  auto u32 = [&](std::uint32_t v) { u16(v & 0xffff), u16(v >> 16); };
  auto element = [&](unsigned group, unsigned elem, const std::string& value) {
    u16(group), u16(elem), u32(static_cast<std::uint32_t>(value.size())), bytes += value;
  };
  element(0x0008, 0x0016, std::string("1.2.840.10008.5.1.4.1.1.481.3") + '\0');
  element(0x0008, 0x0060, "RTSTRUCT");
  for (int i = 0; i < depth; ++i) u16(0x3006), u16(0x0039), u32(0xffffffff), u16(0xfffe), u16(0xe000), u32(0xffffffff);
  for (int i = 0; i < depth; ++i) u16(0xfffe), u16(0xe00d), u32(0), u16(0xfffe), u16(0xe0dd), u32(0);
  return bytes;
}

// Issue 15, cause 1: DCMTK's parser recurses per sequence level; a hostile depth is refused
// before it is parsed, not a stack overflow.
TEST_F(Dicom, DeeplyNestedSequencesRefusedBeforeParsing) {
  const fs::path p = dir_ / "deep.dcm";
  std::ofstream(p, std::ios::binary) << deeplyNestedRtStruct(200000);
  auto r = readRtStruct(p);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidInput);
  EXPECT_NE(r.error().message.find("deep.dcm: DICOM sequences nested more than 64 deep"), std::string::npos) << r.error().message;
  // A shallow nesting is parsed and judged on its content.
  std::ofstream(p, std::ios::binary | std::ios::trunc) << deeplyNestedRtStruct(8);
  r = readRtStruct(p);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message.find("nested"), std::string::npos) << r.error().message;
}

// A deflated data set is inflated under a budget before it is parsed: past it, the file is
// refused by name (a 2 MB deflated file of zeros inflated to 4.1 GB and ended in an
// out-of-memory exit). Within it, the deflated file reads as the plain one does.
TEST_F(Dicom, DeflatedDataSetsInflateUnderABudget) {
  TestRoi roi{1, "box", "ORGAN", std::nullopt, {}};
  for (double z : {0.0, 2.0, 4.0}) roi.contours.push_back(closedContour(square(-6, -6, 6, 6), z));
  TestRtStruct rt;
  rt.rois = {roi};
  const fs::path plain = write(rt), deflated = dir_ / "deflated.dcm";
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(plain.c_str()).good());
  ASSERT_TRUE(file.saveFile(deflated.c_str(), EXS_DeflatedLittleEndianExplicit).good());
  const auto tooMuch = checkDicomNesting(deflated, false, kMaxDicomNesting, 100);
  ASSERT_FALSE(tooMuch);
  EXPECT_EQ(tooMuch.error().code, Errc::ResourceLimit);
  EXPECT_NE(tooMuch.error().message.find("deflated.dcm: its deflated data set inflates to more than 100 B"), std::string::npos)
      << tooMuch.error().message;
  EXPECT_TRUE(checkDicomNesting(plain, false, kMaxDicomNesting, 100)) << "a plain file is not inflated";
  auto a = readRtStruct(plain), b = readRtStruct(deflated);
  ASSERT_TRUE(a && b) << (b ? "" : b.error().message);
  EXPECT_EQ(b->contours.features[0].slices.size(), a->contours.features[0].slices.size());
}

TEST_F(Dicom, NeverCrashesOnTruncatedFiles) {
  TestRtStruct rt = oneRoi(closedContour(square(0, 0, 4, 4), 1));
  const fs::path p = write(rt);
  std::string bytes;
  {
    std::ifstream in(p, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  int failures = 0;
  for (std::size_t cut = 0; cut < bytes.size(); cut += 17) {
    const fs::path t = dir_ / "cut.dcm";
    std::ofstream(t, std::ios::binary | std::ios::trunc) << bytes.substr(0, cut);
    auto r = readRtStruct(t);
    if (!r) {
      ++failures;
      EXPECT_EQ(r.error().message.rfind(t.string() + ": ", 0), 0u) << r.error().message;
    }
  }
  EXPECT_GT(failures, 0);
}

// ---------------------------------------------------------------------------------------
// Reference CT

// A 40 x 30 CT of 0.8 x 0.9 mm pixels off the origin, on the given slices.
test::TestCt latticeCt(std::vector<double> sliceZ) {
  test::TestCt ct;
  ct.columns = 40;
  ct.rows = 30;
  ct.spacingX = 0.8;
  ct.spacingY = 0.9;
  ct.originX = -15.2;
  ct.originY = -12.6;
  ct.sliceZ = std::move(sliceZ);
  return ct;
}

TEST_F(Dicom, ReferenceGridLiesOnTheCtLattice) {
  test::TestCt ct = latticeCt({-5, -2.5, 0, 2.5, 5, 7.5});
  test::writeTestCtSeries(ct, dir_ / "ct");
  TestRtStruct rtFile;
  TestRoi roi{1, "organ", "ORGAN", std::nullopt, {}};
  for (double z : {-2.5, 0.0, 2.50004, 5.0}) roi.contours.push_back(closedContour(square(-6, -5, 7, 6), z));
  rtFile.rois = {roi};
  write(rtFile, "ct/rt.dcm");  // an RTSTRUCT beside the images is ignored by the series reader

  auto series = readCtSeries(dir_ / "ct");
  ASSERT_TRUE(series) << series.error().message;
  EXPECT_EQ(series->columns, 40);
  EXPECT_EQ(series->rows, 30);
  EXPECT_DOUBLE_EQ(series->spacingX, 0.8);
  EXPECT_DOUBLE_EQ(series->spacingY, 0.9);
  EXPECT_EQ(series->sliceZ, ct.sliceZ);
  EXPECT_EQ(series->files.size(), 6u);
  ASSERT_EQ(series->sopInstanceUids.size(), 6u);
  ASSERT_EQ(series->sopClassUids.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(series->sopInstanceUids[k], test::testCtInstanceUid(ct, k));
    EXPECT_EQ(series->sopClassUids[k], "1.2.840.10008.5.1.4.1.1.2");  // CT Image Storage
  }

  auto r = readRtStruct(dir_ / "ct" / "rt.dcm");
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(placeOnCtSlices(r->contours, *series, 0.01));
  GridOptions o;
  o.reference = gridReferenceOf(*series);
  const Built b = buildCpu(r->contours, o);
  const Grid& g = b.volume.grid;
  // One background pixel around the CT: CT pixel (i, j) is grid pixel (i+1, j+1); the layers
  // are the CT slices that hold contours, one background layer below and above.
  EXPECT_EQ(g.nx, 42);
  EXPECT_EQ(g.ny, 32);
  EXPECT_EQ(g.nz, 6);
  EXPECT_DOUBLE_EQ(g.originX, -15.2 - 0.8);
  EXPECT_DOUBLE_EQ(g.originY, -12.6 - 0.9);
  EXPECT_EQ(g.layerZ, (std::vector<double>{-5, -2.5, 0, 2.5, 5, 7.5}));
  expectClosed(b, r->contours);
  // Labels on CT pixel centres: inside the square, outside it, and on CT slices without contours.
  EXPECT_EQ(labelAt(b.volume, -15.2 + 0.8 * 20, -12.6 + 0.9 * 15, 0), labelOfFeature(0));
  EXPECT_EQ(labelAt(b.volume, -15.2 + 0.8 * 2, -12.6 + 0.9 * 15, 0), kBackground);
  EXPECT_EQ(labelAt(b.volume, -15.2 + 0.8 * 20, -12.6 + 0.9 * 15, -5), kBackground);

  // Contours reaching beyond the CT: the grid grows by whole CT pixels, still on its lattice.
  r->contours.features[0].slices[0].contours[0].points[1].x = 30;
  auto wide = makeGrid(r->contours, o);
  ASSERT_TRUE(wide) << wide.error().message;
  EXPECT_DOUBLE_EQ(wide->originX, -15.2 - 0.8);
  const double lastCentre = wide->originX + (wide->nx - 1) * 0.8;
  EXPECT_GT(lastCentre, 30);
  EXPECT_LE(lastCentre, 30 + 2 * 0.8 + 1e-9);
  const double steps = (lastCentre - ct.originX) / 0.8;
  EXPECT_NEAR(steps, std::round(steps), 1e-9);

  // A contour plane between CT slices is an error naming it and the nearest CT slice.
  auto between = readRtStruct(dir_ / "ct" / "rt.dcm");
  ASSERT_TRUE(between);
  between->contours.features[0].slices[1].z = 1.2;
  auto placed = placeOnCtSlices(between->contours, *series, 0.01);
  ASSERT_FALSE(placed);
  EXPECT_NE(placed.error().message.find("feature \"organ\" (#0), slice z=1.2 (#1): not on a slice of the reference series"),
            std::string::npos)
      << placed.error().message;
  EXPECT_NE(placed.error().message.find("nearest z=0"), std::string::npos);
  EXPECT_FALSE(makeGrid(between->contours, o));
}

// A partial reference series (one slice, as many shared plans carry): its lattice places the
// surfaces in-plane, the contours keep their planes, with a warning; a plane between two
// neighbouring slices of a whole series is still an error.
TEST_F(Dicom, APartialReferenceSeriesGivesTheLatticeAndTheContoursThePlanes) {
  test::TestCt ct = latticeCt({0});
  test::writeTestCtSeries(ct, dir_ / "ct");
  TestRtStruct rtFile;
  TestRoi roi{1, "organ", "ORGAN", std::nullopt, {}};
  for (double z : {-2.5, 0.0, 2.5, 5.0}) roi.contours.push_back(closedContour(square(-6, -5, 7, 6), z));
  rtFile.rois = {roi};
  write(rtFile, "rt.dcm");
  ReadOptions read;
  read.referenceSeries = dir_ / "ct";
  auto contours = readContours(dir_ / "rt.dcm", read);
  ASSERT_TRUE(contours) << contours.error().message;
  EXPECT_TRUE(std::any_of(contours->warnings.begin(), contours->warnings.end(), [](const std::string& w) {
    return w.find("has no slice at 3 contour plane(s) (z=-2.5 to 5)") != std::string::npos;
  }));
  ASSERT_TRUE(contours->reference);
  GridOptions o;
  o.reference = contours->reference;  // as build() takes it
  auto grid = makeGrid(*contours, o);
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_DOUBLE_EQ(grid->originX, -15.2 - 0.8);
  EXPECT_DOUBLE_EQ(grid->spacingY, 0.9);
  EXPECT_EQ(grid->layerZ, (std::vector<double>{-5, -2.5, 0, 2.5, 5, 7.5}));
  const Built b = buildCpu(*contours, o);
  expectClosed(b, *contours);

  // Two slices 30 mm apart of a 3 mm series (its Slice Thickness says so): the planes between
  // lie where slices are missing; two structures drawn on one plane off the series, their z
  // within the tolerance, share it.
  fs::remove_all(dir_ / "ct");
  ct.sliceZ = {0, 30};
  ct.sliceThickness = 3;
  test::writeTestCtSeries(ct, dir_ / "ct");
  TestRoi other{2, "other", "ORGAN", std::nullopt, {}};
  for (double z : {6.0, 9.004}) other.contours.push_back(closedContour(square(8, 8, 12, 12), z));
  roi.contours.clear();
  for (double z : {0.0, 3.0, 6.0, 9.0}) roi.contours.push_back(closedContour(square(-6, -5, 7, 6), z));
  rtFile.rois = {roi, other};
  write(rtFile, "rt.dcm");
  auto sparse = readContours(dir_ / "rt.dcm", read);
  ASSERT_TRUE(sparse) << sparse.error().message;
  ASSERT_TRUE(sparse->reference);
  EXPECT_EQ(sparse->reference->sliceZ, (std::vector<double>{0, 3, 6, 9, 30}));
}

// A CT twice as fine as the contours (1 mm slices, contours every 2 mm): the CT slices between
// contour planes are the between-slice model's (the slab rule here), never background. Each
// structure is one piece, and its mask on the CT grid has no empty slice and the slab rule's
// volume.
TEST_F(Dicom, CtFinerThanTheContourPlanes) {
  test::TestCt ct;
  ct.columns = 50;
  ct.rows = 50;
  ct.originX = -25;
  ct.originY = -25;
  for (int k = 0; k <= 24; ++k) ct.sliceZ.push_back(k);
  test::writeTestCtSeries(ct, dir_ / "ct");
  TestRtStruct rtFile;
  TestRoi body{1, "BODY", "EXTERNAL", std::nullopt, {}}, organ{2, "organ", "ORGAN", std::nullopt, {}};
  for (int z = 2; z <= 20; z += 2) body.contours.push_back(closedContour(square(-20.5, -20.5, 20.5, 20.5), z));
  for (int z = 8; z <= 14; z += 2) organ.contours.push_back(closedContour(square(-5.5, -5.5, 5.5, 5.5), z));
  rtFile.rois = {body, organ};
  write(rtFile, "rt.dcm");
  auto series = readCtSeries(dir_ / "ct");
  auto r = readRtStruct(dir_ / "rt.dcm");
  ASSERT_TRUE(series && r);
  ASSERT_TRUE(placeOnCtSlices(r->contours, *series, 0.01));
  GridOptions o;
  o.reference = gridReferenceOf(*series);
  const Built b = buildCpu(r->contours, o);
  EXPECT_EQ(b.volume.grid.layerZ, (std::vector<double>{0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22}));
  expectClosed(b, r->contours);
  for (int f = 0; f < 2; ++f) EXPECT_EQ(b.stats(f).components, 1) << r->contours.features[static_cast<std::size_t>(f)].name;

  auto cut = cutToReference(b.volume, *o.reference, 2);
  ASSERT_TRUE(cut) << cut.error().message;
  EXPECT_EQ(cut->dropped, (std::vector<std::size_t>{0, 0}));
  const LabelVolume& v = cut->volume;
  ASSERT_EQ(v.grid.nz, 25);
  for (int f = 0; f < 2; ++f) {
    const bool isBody = r->contours.features[static_cast<std::size_t>(f)].name == "BODY";
    std::vector<std::size_t> perSlice(25, 0);
    for (int k = 0; k < 25; ++k)
      for (int j = 0; j < 50; ++j)
        for (int i = 0; i < 50; ++i) {
          const Label l = v.at(i, j, k);  // the partition: the organ's voxels are BODY's too
          perSlice[static_cast<std::size_t>(k)] += l == labelOfFeature(f) || (isBody && l != kBackground);
        }
    // Contours on planes first .. last, 2 mm apart: slabs from first - 1 to last + 1 mm; a CT slice
    // on a slab boundary goes to the lower layer's side.
    const int first = isBody ? 2 : 8, last = isBody ? 20 : 14;
    const std::size_t area = isBody ? 41 * 41 : 11 * 11;
    for (int k = 0; k < 25; ++k) {
      const bool inside = k >= first && k <= last + 1;
      EXPECT_EQ(perSlice[static_cast<std::size_t>(k)], inside ? area : 0u) << (isBody ? "BODY" : "organ") << ", CT slice " << k;
    }
  }
}

// Selecting ROIs does not change a selected ROI's surface: the default grid's pixel size and
// lattice come from every ROI of the file, the grid only covering the selected ones.
TEST_F(Dicom, SelectionKeepsTheDefaultLattice) {
  TestRtStruct rtFile;
  TestRoi small{1, "small", "ORGAN", std::nullopt, {}}, far{2, "far", "ORGAN", std::nullopt, {}};
  for (double z : {0.0, 2.5, 5.0}) {
    small.contours.push_back(closedContour(square(-5.3, -4.1, 6.2, 5.7), z));
    far.contours.push_back(closedContour(square(150, 90, 190, 130), z));
  }
  rtFile.rois = {small, far};
  write(rtFile, "two.dcm");
  auto all = readRtStruct(dir_ / "two.dcm");
  RtStructOptions only;
  only.roiPatterns = {"small"};
  auto selected = readRtStruct(dir_ / "two.dcm", only);
  ASSERT_TRUE(all && selected);
  ASSERT_EQ(selected->contours.features.size(), 1u);
  EXPECT_TRUE(selected->contours.fileExtent.has_value());
  const Built a = buildCpu(all->contours, {}), b = buildCpu(selected->contours, {});
  EXPECT_DOUBLE_EQ(a.volume.grid.spacingX, b.volume.grid.spacingX);
  EXPECT_LT(b.volume.grid.nx, a.volume.grid.nx / 4) << "the grid covers the selection only";
  const double shift = (b.volume.grid.originX - a.volume.grid.originX) / a.volume.grid.spacingX;
  EXPECT_NEAR(shift, std::round(shift), 1e-9) << "on the whole file's lattice";
  EXPECT_NEAR(a.stats(0).volume, b.stats(0).volume, 1e-9 * a.stats(0).volume);
  EXPECT_EQ(a.stats(0).triangles, b.stats(0).triangles);
}

// Files in the CT folder that do not start like DICOM are passed over unparsed (a large
// file of zeros cost DCMTK a minute of empty elements: 200 MB took 9 s, now under 1 s).
TEST_F(Dicom, NonDicomFilesInTheCtFolderAreSkippedUnread) {
  test::TestCt ct;
  ct.sliceZ = {0, 2.5};
  test::writeTestCtSeries(ct, dir_ / "ct");
  std::ofstream(dir_ / "ct" / "zeros.bin", std::ios::binary) << std::string(1 << 20, '\0');
  std::ofstream(dir_ / "ct" / "notes.txt") << "scanner notes\n";
  auto series = readCtSeries(dir_ / "ct");
  ASSERT_TRUE(series) << series.error().message;
  EXPECT_EQ(series->sliceZ, ct.sliceZ);
  EXPECT_EQ(series->files.size(), 2u);
}

TEST_F(Dicom, ReferenceSeriesErrors) {
  auto r = readCtSeries(dir_ / "nothing");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::Io);
  fs::create_directories(dir_ / "empty");
  std::ofstream(dir_ / "empty" / "readme.txt") << "no images here\n";
  r = readCtSeries(dir_ / "empty");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("no DICOM images"), std::string::npos);

  test::TestCt oblique;
  oblique.sliceZ = {0, 1};
  oblique.orientation = {1, 0, 0, 0, 0.8660254, -0.5};
  test::writeTestCtSeries(oblique, dir_ / "oblique");
  r = readCtSeries(dir_ / "oblique");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("Image Orientation (Patient) is 1\\0\\0\\0\\0.8660254\\-0.5; only axial"), std::string::npos)
      << r.error().message;

  // Issue 15, cause 2: one slice moved by 1e12 mm is refused, naming the file.
  test::TestCt far;
  far.sliceZ = {0, 1, 1e12};
  test::writeTestCtSeries(far, dir_ / "far");
  r = readCtSeries(dir_ / "far");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("ct_2.dcm: Image Position (Patient) (0020,0032) value 1e+12 is beyond 1e+07 mm"),
            std::string::npos)
      << r.error().message;

  test::TestCt a, b;
  a.sliceZ = {0, 1};
  b.sliceZ = {2};
  b.seriesUid = "1.2.3.4";
  test::writeTestCtSeries(a, dir_ / "two");
  test::writeTestCtSeries(b, dir_ / "two" / "sub");
  fs::rename(dir_ / "two" / "sub" / "ct_0.dcm", dir_ / "two" / "other.dcm");
  r = readCtSeries(dir_ / "two");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("holds more than one series"), std::string::npos) << r.error().message;

  // Two images that claim one SOP Instance UID (a copy at another z).
  test::TestCt copy = a;
  copy.sliceZ = {2};
  test::writeTestCtSeries(a, dir_ / "dup");
  test::writeTestCtSeries(copy, dir_ / "dup" / "sub");
  fs::rename(dir_ / "dup" / "sub" / "ct_0.dcm", dir_ / "dup" / "copy.dcm");
  r = readCtSeries(dir_ / "dup");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("SOP Instance UID " + test::testCtInstanceUid(a, 0) + " is also that of"), std::string::npos)
      << r.error().message;
}

// ---------------------------------------------------------------------------------------
// The public samples (../shared/data/rtstruct, see its SOURCES.md).

struct SampleRun {
  RtStructure rt;
  Built built;
  std::vector<MeshStats> stats;  // per feature
  double seconds = 0;
};

SampleRun runSample(const fs::path& file, const fs::path& reference = {}) {
  const auto t0 = std::chrono::steady_clock::now();
  SampleRun run;
  auto r = readRtStruct(file);
  EXPECT_TRUE(r) << r.error().message;
  if (!r) return run;
  run.rt = std::move(*r);
  GridOptions o;  // the CLI's default: 256 pixels along the longer side
  if (!reference.empty()) {
    auto ct = readCtSeries(reference);
    EXPECT_TRUE(ct) << ct.error().message;
    if (!ct) return run;
    EXPECT_TRUE(placeOnCtSlices(run.rt.contours, *ct, 0.01));
    o = {};
    o.reference = gridReferenceOf(*ct);
  }
  run.built = buildCpu(run.rt.contours, o);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s: %zu ROIs read, %zu surfaces, %.3f s (CPU pipeline)\n", file.filename().c_str(), run.rt.rois.size(),
              run.rt.contours.features.size(), run.seconds);
  for (std::size_t f = 0; f < run.rt.contours.features.size(); ++f) {
    run.stats.push_back(run.built.stats(static_cast<int>(f)));
    const MeshStats& s = run.stats.back();
    std::printf("  %-12s volume %10.1f mm3 closed %s\n", run.rt.contours.features[f].name.c_str(), s.volume,
                s.closed ? "yes" : "NO");
    EXPECT_TRUE(s.closed && s.manifold && s.oriented) << run.rt.contours.features[f].name;
    EXPECT_GT(s.volume, 0) << run.rt.contours.features[f].name;
  }
  return run;
}

const fs::path kSamples = SCANSURF_RTSTRUCT_SAMPLES;

// The public samples live beside the repository (../shared/data/rtstruct), not in it: a clone
// without them skips these tests, saying so.
class RtStructSamples : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kSamples)) GTEST_SKIP() << "no public RTSTRUCT samples at " << kSamples << " (../shared beside the clone)";
  }
};

TEST_F(RtStructSamples, PydicomWithoutFileHeader) {
  const fs::path file = kSamples / "pydicom-rtstruct.dcm";
  ASSERT_TRUE(fs::exists(file)) << file;
  EXPECT_FALSE(hasDicomPreamble(file));
  const SampleRun run = runSample(file);
  ASSERT_EQ(run.rt.rois.size(), 3u);
  ASSERT_EQ(run.rt.contours.features.size(), 1u);
  EXPECT_EQ(run.rt.contours.features[0].name, "patient");
  EXPECT_EQ(run.rt.contours.features[0].color, (Rgb{220, 160, 120}));
  EXPECT_EQ(run.rt.rois[0].interpretedType, "EXTERNAL");
  EXPECT_EQ(run.rt.warnings.size(), 2u);  // the two POINT ROIs, one warning each
}

TEST_F(RtStructSamples, MockSquareWithHole) {
  const SampleRun run = runSample(kSamples / "rt-utils" / "mock_data_rt.dcm");
  ASSERT_GE(run.rt.contours.features.size(), 1u);
  ASSERT_EQ(run.stats.size(), 1u);
  EXPECT_GE(run.stats[0].genus, 1);  // the hole goes through
}

TEST_F(RtStructSamples, MimPhantomOnItsCt) {
  const fs::path dir = kSamples / "rt-utils" / "mim_phantom";
  const SampleRun run = runSample(dir / "rt.dcm", dir);
  ASSERT_EQ(run.rt.contours.features.size(), 4u);
  const Grid& g = run.built.volume.grid;
  EXPECT_EQ(g.nx, 514);
  EXPECT_EQ(g.ny, 514);
  EXPECT_EQ(g.nz, 5);  // the 3 CT slices (of 5) that hold contours, a background layer each side
  EXPECT_NEAR(g.originX, -125 - 0.488281, 1e-9);
  // The same set with its image references stripped reads the same ROIs and volumes.
  const SampleRun stripped = runSample(kSamples / "rt-utils" / "non_existent_reference_rt.dcm", dir);
  ASSERT_EQ(stripped.rt.contours.features.size(), 4u);
  for (int f = 0; f < 4; ++f) EXPECT_NEAR(stripped.stats[f].volume, run.stats[f].volume, 1e-6);
}

}  // namespace
}  // namespace scansurf
